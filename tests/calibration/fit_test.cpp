// Least squares: exact recoveries, residuals worked out by hand, and the refusals.
#include "calibration/fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace marsokhod::calibration {
namespace {

TEST(FitLine, RecoversAnExactLine) {
  const std::vector<double> x{250, 300, 350, 400};
  std::vector<double> y;
  for (double v : x) y.push_back(0.06768 * v - 41.0823);
  const LineFit fit = fit_line(x, y);
  EXPECT_NEAR(fit.gain, 0.06768, 1e-12);
  EXPECT_NEAR(fit.offset, -41.0823, 1e-9);
  EXPECT_NEAR(fit.residuals.rms, 0.0, 1e-9);
  EXPECT_NEAR(fit.r_squared, 1.0, 1e-12);
}

TEST(FitLine, ResidualsOfFourPointsByHand) {
  // y = 0, 1, 1, 2 at x = 0, 1, 2, 3: slope 0.6, offset 0.1, residuals −0.1, 0.3, −0.3, 0.1.
  const LineFit fit = fit_line(std::vector<double>{0, 1, 2, 3}, std::vector<double>{0, 1, 1, 2});
  EXPECT_NEAR(fit.gain, 0.6, 1e-12);
  EXPECT_NEAR(fit.offset, 0.1, 1e-12);
  EXPECT_NEAR(fit.residuals.rms, std::sqrt(0.2 / 4), 1e-12);
  EXPECT_NEAR(fit.residuals.max_abs, 0.3, 1e-12);
  EXPECT_EQ(fit.residuals.count, 4U);
}

TEST(FitLine, RefusesDataThatDoesNotDetermineALine) {
  EXPECT_THROW(fit_line(std::vector<double>{1}, std::vector<double>{2}), std::invalid_argument);
  EXPECT_THROW(fit_line(std::vector<double>{3, 3, 3}, std::vector<double>{1, 2, 3}),
               std::invalid_argument);
  EXPECT_THROW(fit_line(std::vector<double>{1, 2}, std::vector<double>{1}),
               std::invalid_argument);
  EXPECT_THROW(fit_line(std::vector<double>{1, NAN}, std::vector<double>{1, 2}),
               std::invalid_argument);
}

TEST(FitLeastSquares, RecoversTheDeltaOfAnFirFilter) {
  // w^k = Σ δ^j ŵ^(k−j) with the thesis' δ (h = 0.0157, con = 0), ŵ a chirp-like signal.
  const std::vector<double> delta{0.0, 0.2452, 0.3742, 0.2798, 0.1008};
  std::vector<double> input;
  for (int k = 0; k < 400; ++k) input.push_back(std::sin(0.001 * k * k) + 0.3 * std::cos(0.2 * k));
  std::vector<std::vector<double>> rows;
  std::vector<double> y;
  for (std::size_t k = delta.size(); k < input.size(); ++k) {
    std::vector<double> row;
    double w = 0.0;
    for (std::size_t j = 0; j < delta.size(); ++j) {
      row.push_back(input[k - j]);
      w += delta[j] * input[k - j];
    }
    rows.push_back(row);
    y.push_back(w);
  }
  const LeastSquaresFit fit = fit_least_squares(rows, y);
  ASSERT_EQ(fit.coefficients.size(), delta.size());
  for (std::size_t j = 0; j < delta.size(); ++j) EXPECT_NEAR(fit.coefficients[j], delta[j], 1e-9);
  EXPECT_LT(fit.residuals.rms, 1e-9);
}

TEST(FitLeastSquares, MinimisesTheSquaredError) {
  // Overdetermined: y = c at three points 1, 2, 6 → c = mean = 3, residuals −2, −1, 3.
  const LeastSquaresFit fit =
      fit_least_squares({{1.0}, {1.0}, {1.0}}, std::vector<double>{1.0, 2.0, 6.0});
  EXPECT_NEAR(fit.coefficients[0], 3.0, 1e-12);
  EXPECT_NEAR(fit.residuals.rms, std::sqrt(14.0 / 3.0), 1e-12);
  EXPECT_NEAR(fit.residuals.max_abs, 3.0, 1e-12);
}

TEST(FitLeastSquares, RefusesRankDeficientOrShortData) {
  // A constant input cannot tell δ^1 from δ^2.
  EXPECT_THROW(fit_least_squares({{1, 1}, {1, 1}, {1, 1}}, std::vector<double>{1, 1, 1}),
               std::invalid_argument);
  EXPECT_THROW(fit_least_squares({{1, 2}}, std::vector<double>{1}), std::invalid_argument);
  EXPECT_THROW(fit_least_squares({{1, 2}, {3}}, std::vector<double>{1, 2}),
               std::invalid_argument);
}

TEST(Statistics, MeanAndPopulationDeviation) {
  const std::vector<double> v{2, 4, 4, 4, 5, 5, 7, 9};
  EXPECT_DOUBLE_EQ(mean(v), 5.0);
  EXPECT_DOUBLE_EQ(standard_deviation(v), 2.0);
  EXPECT_THROW(mean(std::vector<double>{}), std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::calibration
