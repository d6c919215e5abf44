// Procedure 4.8's fit: the least-squares δ of (4.4) with its standard errors (response.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "calibration/procedure.hpp"
#include "calibration/response.hpp"

namespace marsokhod::calibration {

namespace {

void check_series(const std::vector<ResponseSeries>& wheels, const ResponseFitSettings& settings) {
  if (settings.order == 0) throw std::invalid_argument("fit_response: the order N must be ≥ 1");
  for (const ResponseSeries& s : wheels) {
    if (s.commanded_radps.size() != s.measured_radps.size()) {
      throw std::invalid_argument("fit_response: ŵ and w of a wheel differ in length");
    }
  }
}

// The least-squares rows [ŵ_(m−1), …, ŵ_(m−N)] → v_m, for m ≥ N of every wheel.
void regression_rows(const std::vector<ResponseSeries>& wheels, std::size_t n,
                     std::vector<std::vector<double>>& rows, std::vector<double>& y) {
  for (const ResponseSeries& s : wheels) {
    for (std::size_t m = n; m < s.measured_radps.size(); ++m) {
      std::vector<double> row(n);
      for (std::size_t j = 1; j <= n; ++j) row[j - 1] = s.commanded_radps[m - j];
      rows.push_back(std::move(row));
      y.push_back(s.measured_radps[m]);
    }
  }
}

// The command's excitation: the covariance of N consecutive ŵ (each wheel's mean removed).
double command_excitation(const std::vector<ResponseSeries>& wheels, std::size_t n) {
  std::vector<std::vector<double>> covariance(n, std::vector<double>(n, 0.0));
  std::size_t count = 0;
  for (const ResponseSeries& s : wheels) {
    const double centre = mean(s.commanded_radps);
    for (std::size_t m = n - 1; m < s.commanded_radps.size(); ++m) {
      for (std::size_t a = 0; a < n; ++a) {
        for (std::size_t b = 0; b < n; ++b) {
          covariance[a][b] +=
              (s.commanded_radps[m - a] - centre) * (s.commanded_radps[m - b] - centre);
        }
      }
      ++count;
    }
  }
  return count > 0 ? eigenvalue_ratio(covariance) : 0.0;
}

// Standard errors of δ¹ … δ^N (index 0: δ⁰, 0): σ²·diag((AᵀA)⁻¹), with the residuals' lag-1
// correlation shrinking the number of independent rows (they are smooth, not white).
std::vector<double> standard_errors(const std::vector<std::vector<double>>& rows,
                                    const std::vector<double>& y,
                                    const std::vector<double>& coefficients) {
  const std::size_t n = coefficients.size();
  std::vector<std::vector<double>> normal(n, std::vector<double>(n, 0.0));
  std::vector<double> residual(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    double predicted = 0.0;
    for (std::size_t a = 0; a < n; ++a) {
      predicted += rows[r][a] * coefficients[a];
      for (std::size_t b = 0; b < n; ++b) normal[a][b] += rows[r][a] * rows[r][b];
    }
    residual[r] = y[r] - predicted;
  }
  double rss = 0.0;
  double lag1 = 0.0;
  for (std::size_t r = 0; r < residual.size(); ++r) {
    rss += residual[r] * residual[r];
    if (r > 0) lag1 += residual[r] * residual[r - 1];
  }
  const double rho = rss > 0.0 ? std::clamp(lag1 / rss, 0.0, 0.99) : 0.0;
  const double inflation = (1.0 + rho) / (1.0 - rho);
  const double sigma2 =
      rss / static_cast<double>(std::max<std::size_t>(rows.size() - n, 1)) * inflation;
  const std::vector<double> diagonal = inverse_diagonal(normal);
  std::vector<double> se(n + 1, 0.0);
  for (std::size_t j = 1; j <= n; ++j) {
    se[j] = diagonal.empty() ? std::numeric_limits<double>::infinity()
                             : std::sqrt(std::max(0.0, sigma2 * diagonal[j - 1]));
  }
  return se;
}

// The problems of a fit whose δ is determined: residuals, and the least certain δ^j.
void judge_response(ResponseFit& fit, const ResponseFitSettings& settings) {
  double worst = 0.0;
  std::size_t worst_j = 0;
  for (std::size_t j = 1; j < fit.standard_error.size(); ++j) {
    if (fit.standard_error[j] > worst) {
      worst = fit.standard_error[j];
      worst_j = j;
    }
  }
  if (fit.residuals.rms > settings.max_residual_radps) {
    fit.problems.push_back("w − ν scatters by " + fixed(fit.residuals.rms) +
                           " rad/s (rms), more than " + fixed(settings.max_residual_radps) +
                           " rad/s: the data is too noisy or the wheels are not free");
  }
  if (!(worst <= settings.max_standard_error)) {
    fit.problems.push_back("δ^" + std::to_string(worst_j) + " = " + fixed(fit.delta[worst_j]) +
                           " is uncertain by ±" + fixed(worst, 4) + " (limit ±" +
                           fixed(settings.max_standard_error, 4) +
                           "): the chirp is too short, covers too few frequencies, or the data "
                           "is too noisy");
  }
}

}  // namespace

ResponseFit fit_response(const std::vector<ResponseSeries>& wheels,
                         const ResponseFitSettings& settings) {
  check_series(wheels, settings);
  ResponseFit fit;
  const std::size_t n = settings.order;
  fit.delta.assign(n + 1, 0.0);
  fit.standard_error.assign(n + 1, 0.0);
  std::size_t shortest = wheels.empty() ? 0 : wheels.front().measured_radps.size();
  for (const ResponseSeries& s : wheels) shortest = std::min(shortest, s.measured_radps.size());
  fit.duration_s = static_cast<double>(shortest) * settings.period_s;
  if (wheels.empty() || fit.duration_s < settings.min_duration_s) {
    fit.problems.push_back("the chirp is too short: " + fixed(fit.duration_s, 1) +
                           " s, need at least " + fixed(settings.min_duration_s, 1) +
                           " s (--duration; the thesis ran 2 min)");
    return fit;
  }
  std::vector<std::vector<double>> rows;
  std::vector<double> y;
  regression_rows(wheels, n, rows, y);
  fit.rows = rows.size();
  fit.excitation = command_excitation(wheels, n);
  if (!(fit.excitation >= settings.min_excitation)) {
    fit.problems.push_back("the command covers too few frequencies to tell " +
                           std::to_string(n) + " lags apart (excitation " +
                           fixed(fit.excitation, 6) + ", need " +
                           fixed(settings.min_excitation, 6) +
                           "): assign a chirp rising to near 1/(2h)");
  }
  LeastSquaresFit ls;
  try {
    ls = fit_least_squares(rows, y);
  } catch (const std::invalid_argument& e) {
    fit.problems.push_back(std::string("δ is not determined by the data (") + e.what() +
                           "): the command must oscillate over many frequencies (a chirp), "
                           "not hold still or repeat one frequency");
    return fit;
  }
  for (std::size_t j = 1; j <= n; ++j) fit.delta[j] = ls.coefficients[j - 1];
  fit.residuals = ls.residuals;
  for (const double d : fit.delta) fit.sum += d;
  fit.standard_error = standard_errors(rows, y, ls.coefficients);
  judge_response(fit, settings);
  return fit;
}

}  // namespace marsokhod::calibration
