// Procedure 4.4 (motor-curve): the fit on synthetic sweeps (exact, too fast, noisy, not
// increasing) and the procedure against the simulator's true W.
#include "calibration/motor_curve.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "calibration/procedures.hpp"
#include "core/adaptation/motor_curve.hpp"
#include "motor_unit_support.hpp"

namespace marsokhod::calibration {
namespace {

using testing::mentions;

// A smooth curve with a dead zone, like the simulator's.
double synthetic_w(double d) {
  const double x = std::max(0.0, d * 24.0 - 1.0);
  return 0.146 * x / (1.0 + 0.146 * x / 16.7);
}

// A sweep up over ramp_s, 1 s at the top, down over ramp_s; the wheels follow the duty with a
// first-order lag (time constant lag_s) and noise of σ noise_radps. wheel i has scale 1 + 0.01·i.
std::vector<MotorCurveSample> synthetic_sweep(double ramp_s, double lag_s, double noise_radps,
                                              double (*curve)(double) = synthetic_w) {
  constexpr double h = 0.0156;
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0.0, noise_radps);
  std::vector<MotorCurveSample> out;
  std::vector<double> speed(3, 0.0);
  double t = 0.0;
  auto add = [&](double d, SweepPhase phase) {
    MotorCurveSample s;
    s.time_s = t;
    s.duty = d;
    s.supply_v = 23.8;
    s.phase = phase;
    for (std::size_t i = 0; i < speed.size(); ++i) {
      const double steady = (1.0 + 0.01 * static_cast<double>(i)) * curve(d) * 23.8 / 24.0;
      speed[i] = steady + (speed[i] - steady) * std::exp(-h / lag_s);
      s.velocity_radps.push_back(speed[i] + (noise_radps > 0.0 ? noise(random) : 0.0));
    }
    out.push_back(s);
    t += h;
  };
  const auto n = static_cast<std::size_t>(ramp_s / h);
  for (std::size_t k = 0; k <= n; ++k) add(static_cast<double>(k) / static_cast<double>(n), SweepPhase::kRising);
  for (std::size_t k = 0; k < 64; ++k) add(1.0, SweepPhase::kTop);
  for (std::size_t k = 0; k <= n; ++k) {
    add(1.0 - static_cast<double>(k) / static_cast<double>(n), SweepPhase::kFalling);
  }
  return out;
}

TEST(MotorCurveFit, RecoversTheMeanCurveOfTheWheels) {
  const MotorCurveFit fit = fit_motor_curve(synthetic_sweep(40.0, 0.04, 0.0), {});
  ASSERT_TRUE(fit.problems.empty()) << fit.problems.front();
  ASSERT_EQ(fit.curve.no_load_speed_radps.size(), 11u);
  EXPECT_EQ(fit.curve.no_load_speed_radps[0], 0.0);
  for (std::size_t g = 1; g < 11; ++g) {
    const double d = fit.curve.duty[g];
    // The mean of the wheels' scales 1.00, 1.01, 1.02; normalised by Ū/U.
    EXPECT_NEAR(fit.curve.no_load_speed_radps[g], 1.01 * synthetic_w(d), 0.004) << "d = " << d;
  }
  EXPECT_LT(fit.max_hysteresis_radps, 0.03);
  EXPECT_NEAR(fit.max_wheel_spread, 0.01, 0.002);
}

TEST(MotorCurveFit, RefusesASweepTooFastForTheMotor) {
  // 0.3 s of lag against a 10 s sweep: the ways up and down disagree.
  const MotorCurveFit fit = fit_motor_curve(synthetic_sweep(10.0, 0.3, 0.0), {});
  EXPECT_TRUE(mentions(fit.problems, "too fast")) << (fit.problems.empty() ? "" : fit.problems[0]);
}

TEST(MotorCurveFit, RefusesASweepTooShortToTabulate) {
  const MotorCurveFit fit = fit_motor_curve(synthetic_sweep(2.0, 0.01, 0.0), {});
  EXPECT_TRUE(mentions(fit.problems, "too few samples"));
}

TEST(MotorCurveFit, RefusesNoisyData) {
  const MotorCurveFit fit = fit_motor_curve(synthetic_sweep(40.0, 0.04, 0.1), {});
  EXPECT_TRUE(mentions(fit.problems, "too noisy"));
}

double dented(double d) { return d > 0.45 && d < 0.55 ? synthetic_w(0.35) : synthetic_w(d); }

TEST(MotorCurveFit, RefusesACurveThatDoesNotIncrease) {
  const MotorCurveFit fit = fit_motor_curve(synthetic_sweep(40.0, 0.01, 0.0, dented), {});
  EXPECT_TRUE(mentions(fit.problems, "not increasing"));
}

TEST(MotorCurveFit, TabulatesADeadZoneWiderThanTheFirstStep) {
  const auto wide = [](double d) { return std::max(0.0, d - 0.12) * 3.0; };
  const MotorCurveFit fit =
      fit_motor_curve(synthetic_sweep(40.0, 0.01, 0.0, +wide), {});
  ASSERT_TRUE(fit.problems.empty()) << fit.problems.front();
  EXPECT_GT(fit.curve.no_load_speed_radps[1], 0.0);
  EXPECT_LT(fit.curve.no_load_speed_radps[1], 0.01);
  EXPECT_FALSE(fit.notes.empty());
  // The table loads: strictly increasing from 0.
  EXPECT_NO_THROW(adaptation::MotorCurve{fit.curve});
}

// Against the simulator: W is the mean of the wheels' true no-load speeds at 24 V.
TEST(MotorCurveSim, RecoversTheUnitsMeanCurveWhereTheNominalTableIsOff) {
  const testing::TestUnit unit = testing::drawn_unit(7);
  const ProcedureResult result = testing::calibrate_unit(unit, "motor-curve", 60.0);
  ASSERT_TRUE(result.accepted()) << result.problems.front();
  EXPECT_EQ(result.procedure, "motor-curve");

  const Params fitted = testing::apply_values(unit, result.values);
  const adaptation::MotorCurve curve(adaptation::select_motor_curve(fitted.motor_curves, 511));
  const adaptation::MotorCurve nominal(
      adaptation::select_motor_curve(unit.params.motor_curves, 511));
  // Tolerance: 1 % of W, at least 0.005 rad/s. (A free wheel of the simulator turns ≈ 0.3 %
  // below MotorTruth's ω0: what the encoders measure is what the driver compares with.)
  double nominal_worst = 0.0;
  for (double d = 0.1; d <= 1.0001; d += 0.1) {
    double truth = 0.0;
    for (std::size_t i = 0; i < kWheelCount; ++i) truth += testing::true_speed(unit, i, d) / 6.0;
    const double tolerance = std::max(0.005, 0.01 * truth);
    EXPECT_NEAR(curve.velocity_radps(d), truth, tolerance) << "d = " << d;
    nominal_worst = std::max(nominal_worst, std::abs(nominal.velocity_radps(d) - truth) / tolerance);
  }
  EXPECT_GT(nominal_worst, 1.0) << "the nominal table would pass: the test proves nothing";
  EXPECT_LT(result.quality.at("max_hysteresis_radps"), 0.03);
  ASSERT_EQ(result.recordings.size(), 2u);
  EXPECT_FALSE(result.recordings[0].gnuplot.empty());
}

TEST(MotorCurveSim, RefusesASweepOfAFewSeconds) {
  const testing::TestUnit unit = testing::drawn_unit(7);
  const ProcedureResult result = testing::calibrate_unit(unit, "motor-curve", 4.0);
  EXPECT_FALSE(result.accepted());
}

}  // namespace
}  // namespace marsokhod::calibration

