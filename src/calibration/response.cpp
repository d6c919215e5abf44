// Procedure 4.8: the chirp on the stand and the least-squares δ of (4.4) (response.hpp).
#include "calibration/response.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "calibration/procedures.hpp"
#include "core/adaptation/motor_curve.hpp"
#include "core/adaptation/no_load_estimator.hpp"
#include "core/adaptation/no_load_velocity.hpp"

namespace marsokhod::calibration {
namespace {

// The diagonal of (AᵀA)⁻¹ by Gauss–Jordan on the small normal matrix; empty when singular.
std::vector<double> inverse_diagonal(std::vector<std::vector<double>> m) {
  const std::size_t n = m.size();
  std::vector<std::vector<double>> inv(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i) inv[i][i] = 1.0;
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t pivot = c;
    for (std::size_t r = c + 1; r < n; ++r) {
      if (std::abs(m[r][c]) > std::abs(m[pivot][c])) pivot = r;
    }
    if (!(std::abs(m[pivot][c]) > 0.0)) return {};
    std::swap(m[c], m[pivot]);
    std::swap(inv[c], inv[pivot]);
    const double p = m[c][c];
    for (std::size_t k = 0; k < n; ++k) {
      m[c][k] /= p;
      inv[c][k] /= p;
    }
    for (std::size_t r = 0; r < n; ++r) {
      if (r == c) continue;
      const double f = m[r][c];
      for (std::size_t k = 0; k < n; ++k) {
        m[r][k] -= f * m[c][k];
        inv[r][k] -= f * inv[c][k];
      }
    }
  }
  std::vector<double> diagonal(n);
  for (std::size_t i = 0; i < n; ++i) diagonal[i] = inv[i][i];
  return diagonal;
}

// The smallest over the largest eigenvalue of a symmetric matrix (cyclic Jacobi).
double eigenvalue_ratio(std::vector<std::vector<double>> a) {
  const std::size_t n = a.size();
  for (int sweep = 0; sweep < 100; ++sweep) {
    double off = 0.0;
    double total = 0.0;
    for (std::size_t p = 0; p < n; ++p) {
      for (std::size_t q = 0; q < n; ++q) {
        total += a[p][q] * a[p][q];
        if (p != q) off += a[p][q] * a[p][q];
      }
    }
    if (off <= 1e-30 * total) break;
    for (std::size_t p = 0; p < n; ++p) {
      for (std::size_t q = p + 1; q < n; ++q) {
        if (a[p][q] == 0.0) continue;
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::hypot(theta, 1.0));
        const double c = 1.0 / std::hypot(t, 1.0);
        const double s = t * c;
        for (std::size_t k = 0; k < n; ++k) {
          const double kp = a[k][p];
          const double kq = a[k][q];
          a[k][p] = c * kp - s * kq;
          a[k][q] = s * kp + c * kq;
        }
        for (std::size_t k = 0; k < n; ++k) {
          const double pk = a[p][k];
          const double qk = a[q][k];
          a[p][k] = c * pk - s * qk;
          a[q][k] = s * pk + c * qk;
        }
      }
    }
  }
  double smallest = std::numeric_limits<double>::infinity();
  double largest = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    smallest = std::min(smallest, a[i][i]);
    largest = std::max(largest, a[i][i]);
  }
  return largest > 0.0 ? std::max(0.0, smallest) / largest : 0.0;
}

}  // namespace

double Chirp::frequency_hz(double t_s) const {
  return start_hz + (end_hz - start_hz) * t_s / duration_s;
}

double Chirp::operator()(double t_s) const {
  const double phase =
      2.0 * std::numbers::pi * (start_hz * t_s + 0.5 * (end_hz - start_hz) * t_s * t_s / duration_s);
  const double step = 2.0 * std::sin(std::numbers::pi * std::min(frequency_hz(t_s) * period_s, 0.5));
  const double amplitude = step > 0.0 ? std::min(amplitude_radps, max_step_radps / step)
                                      : amplitude_radps;
  return center_radps + amplitude * std::sin(phase);
}

std::vector<double> predict_response(const std::vector<double>& delta,
                                     const std::vector<double>& commanded_radps) {
  std::vector<double> nu(commanded_radps.size(), 0.0);
  if (commanded_radps.empty()) return nu;
  const auto n = static_cast<std::ptrdiff_t>(commanded_radps.size());
  for (std::ptrdiff_t m = 0; m < n; ++m) {
    double sum = 0.0;
    for (std::size_t j = 0; j < delta.size(); ++j) {
      const std::ptrdiff_t k = m - static_cast<std::ptrdiff_t>(j);
      double w_hat = 0.0;
      if (k < 0) {
        w_hat = commanded_radps.front();
      } else if (k < n) {
        w_hat = commanded_radps[static_cast<std::size_t>(k)];
      }
      sum += delta[j] * w_hat;
    }
    nu[static_cast<std::size_t>(m)] = sum;
  }
  return nu;
}

ResponseFit fit_response(const std::vector<ResponseSeries>& wheels,
                         const ResponseFitSettings& settings) {
  if (settings.order == 0) throw std::invalid_argument("fit_response: the order N must be ≥ 1");
  for (const ResponseSeries& s : wheels) {
    if (s.commanded_radps.size() != s.measured_radps.size()) {
      throw std::invalid_argument("fit_response: ŵ and w of a wheel differ in length");
    }
  }
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

  // Rows: [ŵ_(m−1), …, ŵ_(m−N)] → v_m, for m ≥ N of every wheel.
  std::vector<std::vector<double>> rows;
  std::vector<double> y;
  for (const ResponseSeries& s : wheels) {
    for (std::size_t m = n; m < s.measured_radps.size(); ++m) {
      std::vector<double> row(n);
      for (std::size_t j = 1; j <= n; ++j) row[j - 1] = s.commanded_radps[m - j];
      rows.push_back(std::move(row));
      y.push_back(s.measured_radps[m]);
    }
  }
  fit.rows = rows.size();

  // The command's excitation: the covariance of N consecutive ŵ (each wheel's mean removed).
  {
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
    fit.excitation = count > 0 ? eigenvalue_ratio(covariance) : 0.0;
    if (!(fit.excitation >= settings.min_excitation)) {
      fit.problems.push_back("the command covers too few frequencies to tell " +
                             std::to_string(n) + " lags apart (excitation " +
                             fixed(fit.excitation, 6) + ", need " +
                             fixed(settings.min_excitation, 6) +
                             "): assign a chirp rising to near 1/(2h)");
    }
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

  // Standard errors: σ²·diag((AᵀA)⁻¹), with the residuals' lag-1 correlation shrinking the
  // number of independent rows (they are smooth, not white).
  std::vector<std::vector<double>> normal(n, std::vector<double>(n, 0.0));
  std::vector<double> residual(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    double predicted = 0.0;
    for (std::size_t a = 0; a < n; ++a) {
      predicted += rows[r][a] * ls.coefficients[a];
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
  double worst = 0.0;
  std::size_t worst_j = 0;
  for (std::size_t j = 1; j <= n; ++j) {
    fit.standard_error[j] =
        diagonal.empty() ? std::numeric_limits<double>::infinity() : std::sqrt(std::max(0.0, sigma2 * diagonal[j - 1]));
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
  return fit;
}

ProcedureResult calibrate_response(Bench& bench, const ProcedureOptions& options) {
  const Params& params = bench.params();
  ProcedureResult result;
  result.procedure = "response";
  result.reference = "Procedure 4.8";
  const double duration_s = duration_of(options, 120.0, result.procedure);
  const int icr = options.icr.value_or(params.cycle.icr);
  const adaptation::MotorCurve curve(adaptation::select_motor_curve(params.motor_curves, icr));
  const double nominal_v = params.motors.nominal_supply_v;
  const std::vector<std::size_t> wheels = all_wheels();

  bench.arrange(stand_at_nominal_supply(
      params, " (Procedure 4.8). The wheels will oscillate faster and faster for " +
                  fixed(duration_s, 0) + " s."));
  bench.start(icr, params.cycle.con);
  const double h = bench.period_s();

  // The chirp of Figure 4.4 up to 0.9 of the Nyquist frequency, each step within 80 % of the
  // duty's slew limit (W′ ≈ 3 rad/s per unit duty).
  Chirp chirp;
  chirp.duration_s = duration_s;
  chirp.period_s = h;
  chirp.end_hz = 0.45 / h;
  chirp.max_step_radps = 0.8 * params.safety.max_duty_step * 3.0;
  const double lead_in_s = 2.0;  // from rest up to the centre, not fitted
  constexpr double kCenter_radps = 1.2;
  chirp.center_radps = kCenter_radps;

  std::vector<ResponseSeries> series(wheels.size());
  std::vector<double> times;
  double supply_v = nominal_v;
  const auto lead_cycles = static_cast<std::size_t>(std::ceil(lead_in_s / h));
  const auto chirp_cycles = static_cast<std::size_t>(std::ceil(duration_s / h));
  for (std::size_t k = 0; k < lead_cycles + chirp_cycles; ++k) {
    const bool lead = k < lead_cycles;
    const double target =
        lead ? kCenter_radps * static_cast<double>(k + 1) / static_cast<double>(lead_cycles)
             : chirp(static_cast<double>(k - lead_cycles) * h);
    MotorVector wanted{};
    for (const std::size_t w : wheels) {
      wanted[w] = adaptation::duty_for_no_load_velocity(curve, target, params.motors.scale[w],
                                                        supply_v, nominal_v);
    }
    const double supply_sent_v = supply_v;  // the U the driver would use for ŵ of this duty
    const BenchSample& s = bench.cycle(wanted);
    if (s.sensors.supply_v > 0.0) supply_v = s.sensors.supply_v;
    if (lead) continue;
    times.push_back(s.time_s);
    for (std::size_t i = 0; i < wheels.size(); ++i) {
      const std::size_t w = wheels[i];
      series[i].commanded_radps.push_back(adaptation::no_load_velocity(
          curve, s.duty[w], params.motors.scale[w], supply_sent_v, nominal_v));
      series[i].measured_radps.push_back(s.velocity_radps[w]);
    }
  }
  bench.stop();

  ResponseFitSettings settings;
  settings.period_s = h;
  const ResponseFit fit = fit_response(series, settings);
  result.problems = fit.problems;

  toml::table entry;
  entry.insert("period_s", std::round(h * 1e6) / 1e6);
  entry.insert("con", bench.con());
  toml::array delta;
  for (const double d : fit.delta) delta.push_back(std::round(d * 1e4) / 1e4);
  entry.insert("delta", std::move(delta));
  toml::array responses;
  responses.push_back(std::move(entry));
  result.values.insert("response", std::move(responses));

  // The configured δ on the same data, for comparison.
  const ResponseParams* configured = nullptr;
  try {
    configured = &adaptation::select_response(params.responses, h, bench.con());
  } catch (const std::invalid_argument&) {
    configured = nullptr;
  }
  std::vector<double> fitted_nu;
  std::vector<double> configured_nu;
  if (!series.empty()) {
    fitted_nu = predict_response(fit.delta, series.front().commanded_radps);
    if (configured != nullptr) {
      std::vector<double> pooled_err;
      for (const ResponseSeries& s : series) {
        const std::vector<double> nu = predict_response(configured->delta, s.commanded_radps);
        for (std::size_t m = settings.order; m < nu.size(); ++m) {
          pooled_err.push_back(s.measured_radps[m] - nu[m]);
        }
      }
      double sum = 0.0;
      for (const double e : pooled_err) sum += e * e;
      if (!pooled_err.empty()) {
        result.quality["rms_residual_configured_radps"] =
            std::sqrt(sum / static_cast<double>(pooled_err.size()));
      }
      configured_nu = predict_response(configured->delta, series.front().commanded_radps);
    }
  }
  result.quality["rms_residual_radps"] = fit.residuals.rms;
  result.quality["max_abs_residual_radps"] = fit.residuals.max_abs;
  result.quality["delta_sum"] = fit.sum;
  result.quality["excitation"] = fit.excitation;
  double worst_se = 0.0;
  for (const double se : fit.standard_error) worst_se = std::max(worst_se, se);
  result.quality["max_standard_error"] = worst_se;
  result.quality["duration_s"] = fit.duration_s;
  result.quality["rows"] = static_cast<double>(fit.rows);
  result.quality["period_s"] = h;
  result.notes.push_back("δ for h = " + fixed(h, 4) + " s, con = " + std::to_string(bench.con()) +
                         "; ŵ used the configured ζ and W_" + std::to_string(icr) +
                         " (calibrate motor-curve and motor-scale first)");

  // Figure 4.5 left: δ^j at t = −j·h.
  Recording coefficients;
  coefficients.name = "response_delta";
  coefficients.title = "Procedure 4.8: coefficients δ^j (cf. Figure 4.5 left)";
  coefficients.columns = {"j", "time_s", "delta_fitted", "standard_error", "delta_configured"};
  for (std::size_t j = 0; j < fit.delta.size(); ++j) {
    const double nominal =
        configured != nullptr && j < configured->delta.size() ? configured->delta[j] : 0.0;
    coefficients.rows.push_back({static_cast<double>(j), -static_cast<double>(j) * h,
                                 fit.delta[j], fit.standard_error[j], nominal});
  }
  coefficients.gnuplot =
      "set termoption noenhanced\nset key autotitle columnhead\n"
      "set title 'Procedure 4.8: δ^j against the time −j·h (cf. Figure 4.5 left)'\n"
      "set xlabel 'time [s]'\nset ylabel 'δ'\nset style fill solid 0.6\n"
      "set boxwidth 0.005\nset xrange [*:0.01]\n"
      "plot 'response_delta.csv' using ($2-0.003):3 with boxes title 'fitted', "
      "'' using ($2-0.003):3:4 with yerrorbars lc 'black' pt 0 title 'standard error', "
      "'' using ($2+0.003):5 with boxes fill pattern 4 title 'configured'\n";
  result.recordings.push_back(std::move(coefficients));

  // Figures 4.4 and 4.5 right: the chirp ŵ, the measured w and ν of the first wheel.
  Recording run;
  run.name = "response_chirp";
  run.title = "Procedure 4.8: chirp, measured w and ν (cf. Figures 4.4, 4.5 right)";
  run.columns = {"time_s", "w_hat_radps", "w_radps", "nu_radps", "w_minus_nu_radps",
                 "nu_configured_radps"};
  if (!series.empty()) {
    const ResponseSeries& s = series.front();
    for (std::size_t m = 0; m < s.measured_radps.size(); ++m) {
      run.rows.push_back({times[m], s.commanded_radps[m], s.measured_radps[m], fitted_nu[m],
                          s.measured_radps[m] - fitted_nu[m],
                          configured_nu.empty() ? std::nan("") : configured_nu[m]});
    }
  }
  run.gnuplot =
      "set termoption noenhanced\nset key autotitle columnhead\n"
      "set multiplot layout 2,1\n"
      "set xlabel 'time [s]'\nset ylabel 'rad/s'\n"
      "plot 'response_chirp.csv' using 1:2 with lines, '' using 1:3 with lines, "
      "'' using 1:4 with lines, '' using 1:5 with lines\n"
      "set title 'the last 3 s, with ν of the configured δ (cf. Figure 4.5 right)'\n"
      "set xrange [GPVAL_DATA_X_MAX-3:GPVAL_DATA_X_MAX]\n"
      "plot 'response_chirp.csv' using 1:2 with linespoints, '' using 1:3 with linespoints, "
      "'' using 1:4 with linespoints, '' using 1:6 with lines dt 2\n"
      "unset multiplot\n";
  result.recordings.push_back(std::move(run));
  return result;
}

}  // namespace marsokhod::calibration
