#include "core/control/velocity_control.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "control_test_support.hpp"
#include "core/control/motion_model.hpp"

namespace marsokhod::control {
namespace {

using testing::expect_invalid_argument;
using testing::figure_4_10_params;
using testing::kInfinity;
using testing::kNaN;

// Hand value, unclipped: hμ = 0.00156, c = (0.3001 − 0.99844·0.3)/0.00156 = 0.36410…
TEST(VelocityControl, MatchesFormula414) {
  const ControlParams params = figure_4_10_params();
  EXPECT_NEAR(velocity_control(0.3, 0.3001, params), (0.3001 - 0.99844 * 0.3) / 0.00156, 1e-12);
  EXPECT_EQ(velocity_control(0.3, -0.7, params), -1.0);  // clipped at −C
  EXPECT_EQ(velocity_control(-0.3, 0.7, params), 1.0);   // clipped at +C
}

// At v = v_d the law returns c = v_d, which holds v: v_d is a fixed point of (4.13).
TEST(VelocityControl, HoldsTheTargetVelocity) {
  const ControlParams params = figure_4_10_params();
  for (const double target : {-0.7, 0.0, 0.45, 0.999}) {
    EXPECT_NEAR(velocity_control(target, target, params), target, 1e-12);
  }
}

// Figure 4.10, top: v0 = 0.3 → v_d = −0.7 (μ = 0.1, C = 1, p0 = 0, h = 0.0156 s). The law
// saturates at c = −C, so v(t) = −1 + 1.3·e^(−tμ) by (4.11) reaches within 1% of the step
// (0.01) at t = ln(1.3/0.31)/μ = 14.335 s and v_d itself at ln(1.3/0.3)/μ = 14.663 s, far
// sooner than the ln(100)/μ = 46 s of an unsaturated first-order response. After that the
// unclipped law shrinks the error by λ ≈ hμ/2 per period.
TEST(VelocityControl, Figure410VelocityCaseReachesTheTargetInTheSaturatedTime) {
  const ControlParams params = figure_4_10_params();
  const double target = -0.7;
  const double one_percent_s = std::log(1.3 / 0.31) / params.rate_per_s;
  const double reach_s = std::log(1.3 / 0.3) / params.rate_per_s;
  const Trajectory run = simulate({0.0, 0.3}, params, testing::steps_for(30.0, params),
                                  [&](const MotionState& state) {
                                    return velocity_control(state.velocity, target, params);
                                  });
  const auto within_one_percent = testing::first_reach(run, {run.states.back().position, target},
                                                       kInfinity, 0.01);
  ASSERT_TRUE(within_one_percent.has_value());
  EXPECT_NEAR(static_cast<double>(*within_one_percent) * params.period_s, one_percent_s,
              params.period_s);
  const std::size_t settled = testing::steps_for(reach_s, params) + 2;
  for (std::size_t k = 0; k < run.states.size(); ++k) {
    const double velocity = run.states[k].velocity;
    ASSERT_LE(std::abs(velocity), params.max_speed) << k;
    if (k > 0) {  // monotone: never turns back, never overshoots v_d
      ASSERT_LE(velocity, run.states[k - 1].velocity) << k;
    }
    ASSERT_GE(velocity, target) << k;
    if (k >= settled) {
      ASSERT_NEAR(velocity, target, 1e-9) << k;
    }
  }
}

// Unclipped, (4.14) under (4.13) multiplies v − v_d by
// λ(hμ) = e^(−hμ) − (1 − e^(−hμ))(1 − hμ)/(hμ) ∈ [0, 1): it converges for every hμ > 0.
TEST(VelocityControl, ConvergesMonotonicallyWithTheFactorLambda) {
  for (const double step_rate : {0.00156, 0.00624, 0.5, 1.0, 3.0}) {
    const ControlParams params{1.0, 1e6, step_rate};  // C large: never clipped here
    const double decay = std::exp(-step_rate);
    const double lambda = decay - (1 - decay) * (1 - step_rate) / step_rate;
    ASSERT_GE(lambda, 0.0);
    ASSERT_LT(lambda, 1.0);
    const double target = 0.25;
    const double velocity = -0.5;
    const MotionState next =
        step({0.0, velocity}, velocity_control(velocity, target, params), params);
    EXPECT_NEAR((next.velocity - target) / (velocity - target), lambda, 1e-12) << step_rate;
  }
  EXPECT_NEAR(std::exp(-1.0), 0.36787944117144233, 1e-15);  // λ(1), quoted in the header
}

// |v_d| > C is allowed: v goes to the bound and the output stays within [−C, C].
TEST(VelocityControl, TargetsBeyondTheBoundDriveTheVelocityToTheBound) {
  const ControlParams params{0.4, 1.4135, 0.0156};
  const Trajectory run = simulate({0.0, 0.0}, params, 5000, [&](const MotionState& state) {
    return velocity_control(state.velocity, 1e6, params);
  });
  EXPECT_NEAR(run.states.back().velocity, params.max_speed, 1e-9);
  for (const double control : run.controls) {
    ASSERT_EQ(control, params.max_speed);
  }
}

TEST(VelocityControl, NeverReturnsNaNOverARandomSweep) {
  const ControlParams params{0.4, 1.4135, 0.0156};
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> exponent(-300.0, 300.0);
  std::uniform_real_distribution<double> sign(-1.0, 1.0);
  for (int i = 0; i < 100000; ++i) {
    const double velocity = std::copysign(std::pow(10.0, exponent(random)), sign(random));
    const double target = i % 5 == 0 ? velocity : std::copysign(std::pow(10.0, exponent(random)),
                                                                sign(random));
    const double control = velocity_control(velocity, target, params);
    ASSERT_TRUE(std::isfinite(control)) << velocity << " " << target;
    ASSERT_LE(std::abs(control), params.max_speed);
  }
}

TEST(VelocityControl, RejectsNaNAndInfiniteInputsByName) {
  const ControlParams params = figure_4_10_params();
  for (const double bad : {kNaN, kInfinity, -kInfinity}) {
    expect_invalid_argument([&] { velocity_control(bad, 0.0, params); },
                            {"velocity_control (4.14)", "velocity"});
    expect_invalid_argument([&] { velocity_control(0.0, bad, params); },
                            {"velocity_control (4.14)", "target_velocity"});
  }
  expect_invalid_argument([] { velocity_control(0.0, 0.0, ControlParams{0.1, -1.0, 0.0156}); },
                          {"max_speed"});
}

}  // namespace
}  // namespace marsokhod::control
