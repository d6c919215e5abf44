#include "calibration/fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace marsokhod::calibration {
namespace {

void require_finite(std::span<const double> values, const char* what) {
  for (double v : values) {
    if (!std::isfinite(v)) throw std::invalid_argument(std::string(what) + " is not finite");
  }
}

}  // namespace

double mean(std::span<const double> values) {
  if (values.empty()) throw std::invalid_argument("mean of no values");
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

double standard_deviation(std::span<const double> values) {
  const double m = mean(values);
  double sum = 0.0;
  for (double v : values) sum += (v - m) * (v - m);
  return std::sqrt(sum / static_cast<double>(values.size()));
}

Residuals residuals_of(std::span<const double> predicted, std::span<const double> measured) {
  if (predicted.size() != measured.size()) {
    throw std::invalid_argument("residuals: " + std::to_string(predicted.size()) +
                                " predictions for " + std::to_string(measured.size()) +
                                " measurements");
  }
  Residuals r;
  r.count = measured.size();
  if (r.count == 0) return r;
  double sum = 0.0;
  for (std::size_t i = 0; i < r.count; ++i) {
    const double e = measured[i] - predicted[i];
    sum += e * e;
    r.max_abs = std::max(r.max_abs, std::abs(e));
  }
  r.rms = std::sqrt(sum / static_cast<double>(r.count));
  return r;
}

LineFit fit_line(std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size()) {
    throw std::invalid_argument("line fit: " + std::to_string(x.size()) + " x values for " +
                                std::to_string(y.size()) + " y values");
  }
  if (x.size() < 2) throw std::invalid_argument("line fit: fewer than two points");
  require_finite(x, "line fit: an x value");
  require_finite(y, "line fit: a y value");
  const double mx = mean(x);
  const double my = mean(y);
  double sxx = 0.0;
  double sxy = 0.0;
  double syy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  const double scale = std::max(1.0, std::abs(mx));
  if (sxx <= 1e-24 * scale * scale * static_cast<double>(x.size())) {
    throw std::invalid_argument("line fit: x does not vary, the slope is undetermined");
  }
  LineFit fit;
  fit.gain = sxy / sxx;
  fit.offset = my - fit.gain * mx;
  std::vector<double> predicted(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) predicted[i] = fit.gain * x[i] + fit.offset;
  fit.residuals = residuals_of(predicted, y);
  const double ss_res = fit.residuals.rms * fit.residuals.rms * static_cast<double>(x.size());
  fit.r_squared = syy > 0.0 ? 1.0 - ss_res / syy : (ss_res == 0.0 ? 1.0 : 0.0);
  return fit;
}

namespace {

using Columns = std::vector<std::vector<double>>;

// A column-major copy of the m × n matrix `rows` (m ≥ n ≥ 1, every row n long, all finite).
Columns column_major(const std::vector<std::vector<double>>& rows, std::size_t measurements) {
  const std::size_t m = rows.size();
  if (m != measurements) {
    throw std::invalid_argument("least squares: " + std::to_string(m) + " rows for " +
                                std::to_string(measurements) + " measurements");
  }
  if (m == 0) throw std::invalid_argument("least squares: no rows");
  const std::size_t n = rows.front().size();
  if (n == 0) throw std::invalid_argument("least squares: no unknowns");
  if (m < n) {
    throw std::invalid_argument("least squares: " + std::to_string(m) + " rows for " +
                                std::to_string(n) + " unknowns");
  }
  Columns a(n, std::vector<double>(m));
  for (std::size_t i = 0; i < m; ++i) {
    if (rows[i].size() != n) {
      throw std::invalid_argument("least squares: row " + std::to_string(i) + " has " +
                                  std::to_string(rows[i].size()) + " values, not " +
                                  std::to_string(n));
    }
    for (std::size_t j = 0; j < n; ++j) a[j][i] = rows[i][j];
  }
  for (const auto& column : a) require_finite(column, "least squares: a matrix entry");
  return a;
}

// Householder reflections, in place: A to upper triangular R, b to Qᵀb. Throws for a column
// that is (numerically) a combination of the previous ones.
void householder_reduce(Columns& a, std::vector<double>& b) {
  const std::size_t n = a.size();
  const std::size_t m = b.size();
  std::vector<double> column_norm(n);
  for (std::size_t j = 0; j < n; ++j) {
    double s = 0.0;
    for (double v : a[j]) s += v * v;
    column_norm[j] = std::sqrt(s);
  }
  for (std::size_t k = 0; k < n; ++k) {
    double norm = 0.0;
    for (std::size_t i = k; i < m; ++i) norm += a[k][i] * a[k][i];
    norm = std::sqrt(norm);
    // A pivot tiny against its column's original size: the column is (numerically) a
    // combination of the previous ones.
    if (norm <= 1e-10 * std::max(column_norm[k], 1e-300)) {
      throw std::invalid_argument("least squares: unknown " + std::to_string(k) +
                                  " is not determined by the data (rank deficient)");
    }
    const double alpha = a[k][k] > 0.0 ? -norm : norm;
    std::vector<double> v(m - k);
    for (std::size_t i = k; i < m; ++i) v[i - k] = a[k][i];
    v[0] -= alpha;
    double vv = 0.0;
    for (double e : v) vv += e * e;
    auto reflect = [&](std::vector<double>& col) {
      double dot = 0.0;
      for (std::size_t i = k; i < m; ++i) dot += v[i - k] * col[i];
      const double f = 2.0 * dot / vv;
      for (std::size_t i = k; i < m; ++i) col[i] -= f * v[i - k];
    };
    for (std::size_t j = k; j < n; ++j) reflect(a[j]);
    reflect(b);
  }
}

}  // namespace

LeastSquaresFit fit_least_squares(const std::vector<std::vector<double>>& rows,
                                  std::span<const double> y) {
  Columns a = column_major(rows, y.size());
  require_finite(y, "least squares: a measurement");
  std::vector<double> b(y.begin(), y.end());
  householder_reduce(a, b);
  const std::size_t n = a.size();
  const std::size_t m = b.size();
  LeastSquaresFit fit;
  fit.coefficients.assign(n, 0.0);
  for (std::size_t k = n; k-- > 0;) {
    double s = b[k];
    for (std::size_t j = k + 1; j < n; ++j) s -= a[j][k] * fit.coefficients[j];
    fit.coefficients[k] = s / a[k][k];
  }
  std::vector<double> predicted(m, 0.0);
  for (std::size_t i = 0; i < m; ++i) {
    for (std::size_t j = 0; j < n; ++j) predicted[i] += rows[i][j] * fit.coefficients[j];
  }
  fit.residuals = residuals_of(predicted, y);
  return fit;
}

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

}  // namespace marsokhod::calibration
