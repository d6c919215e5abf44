// Least squares for the calibration procedures, with the residuals a fit is judged by.
#pragma once

#include <span>
#include <string>
#include <vector>

namespace marsokhod::calibration {

struct Residuals {
  double rms = 0.0;
  double max_abs = 0.0;
  std::size_t count = 0;
};

// y ≈ gain·x + offset by least squares. Throws std::invalid_argument for fewer than two points,
// mismatched lengths, non-finite values, or x that does not vary.
struct LineFit {
  double gain = 0.0;
  double offset = 0.0;
  Residuals residuals;
  double r_squared = 0.0;  // 1 − SS_res/SS_tot (1 when y does not vary and the fit is exact)
};
LineFit fit_line(std::span<const double> x, std::span<const double> y);

// The coefficients c minimising |A·c − y|² (A has rows.size() rows of equal length n), by
// Householder QR. Throws std::invalid_argument when there are fewer rows than unknowns, rows of
// unequal length, non-finite values, or A is rank deficient (a column that is numerically a
// combination of the others: the data does not determine the coefficients).
struct LeastSquaresFit {
  std::vector<double> coefficients;
  Residuals residuals;
};
LeastSquaresFit fit_least_squares(const std::vector<std::vector<double>>& rows,
                                  std::span<const double> y);

// The diagonal of m⁻¹ by Gauss–Jordan, for a small (normal) matrix; empty when m is singular.
std::vector<double> inverse_diagonal(std::vector<std::vector<double>> m);

// The smallest over the largest eigenvalue of a symmetric matrix (cyclic Jacobi); 0 when the
// largest is not positive.
double eigenvalue_ratio(std::vector<std::vector<double>> a);

Residuals residuals_of(std::span<const double> predicted, std::span<const double> measured);

double mean(std::span<const double> values);          // throws on empty input
double standard_deviation(std::span<const double> values);  // population σ; throws on empty

}  // namespace marsokhod::calibration
