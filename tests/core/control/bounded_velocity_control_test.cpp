#include "core/control/bounded_velocity_control.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "control_test_support.hpp"
#include "core/control/motion_model.hpp"
#include "core/control/velocity_control.hpp"

namespace marsokhod::control {
namespace {

using testing::expect_invalid_argument;
using testing::figure_4_10_params;
using testing::kInfinity;
using testing::kNaN;

// Figure 4.10, bottom: v0 = −0.4, p0 = 0, v_d = 0.45, p ∈ [−5, 5] (μ = 0.1, C = 1,
// h = 0.0156 s). By (4.10)/(4.11): +C lifts v from −0.4 to 0.45 in ln(1.4/0.55)/μ = 9.343 s;
// v_d > 0 for ever, so the upper bound takes over where braking with −C from 0.45 stops at 5
// (braking distance (0.45 − ln 1.45)/μ = 0.784, braking time ln(1.45)/μ = 3.716 s): at rest at
// 5 after 20.553 s in continuous time. Sampled, the state is exactly at rest on the bound
// (1e-12) within three periods of that, and stays there; p stays in [−5, 5] exactly (no
// tolerance) and |v| ≤ C all run long.
TEST(BoundedVelocityControl, Figure410BoundedCaseEndsAtRestOnTheBound) {
  const ControlParams params = figure_4_10_params();
  const double rate = params.rate_per_s;
  const double target = 0.45;
  const MotionState start{0.0, -0.4};
  const double accelerate_s = std::log(1.4 / 0.55) / rate;
  const double accelerated_m = closed_form(start, 1.0, rate, accelerate_s).position;
  const double braking_m = (target - std::log1p(target)) / rate;
  const double rest_s =
      accelerate_s + (5.0 - braking_m - accelerated_m) / target + std::log1p(target) / rate;
  ASSERT_NEAR(rest_s, 20.553, 1e-3);
  const Trajectory run = simulate(start, params, testing::steps_for(rest_s + 5.0, params),
                                  [&](const MotionState& state) {
                                    return bounded_velocity_control(state, target, -5.0, 5.0,
                                                                    params);
                                  });
  for (const MotionState& state : run.states) {
    ASSERT_GE(state.position, -5.0);
    ASSERT_LE(state.position, 5.0);
    ASSERT_LE(std::abs(state.velocity), params.max_speed * (1 + 1e-15));
  }
  const auto at_rest = testing::first_reach(run, {5.0, 0.0}, 1e-12, 1e-12);
  ASSERT_TRUE(at_rest.has_value());
  const double at_rest_s = static_cast<double>(*at_rest) * params.period_s;
  EXPECT_GE(at_rest_s, rest_s);
  EXPECT_LE(at_rest_s, rest_s + 3 * params.period_s);
  for (std::size_t k = *at_rest; k < run.states.size(); ++k) {
    ASSERT_NEAR(run.states[k].position, 5.0, 1e-12) << k;
    ASSERT_NEAR(run.states[k].velocity, 0.0, 1e-12) << k;
  }
}

// Between samples the model's p (4.10) may pass the bound only in the one period in which v
// turns from + to − on arrival, by at most about μC·h²/20 (1.2e-6 here, 6.9e-6 rad for the
// joints): checked on 50 points inside every period, for several approaches and targets.
TEST(BoundedVelocityControl, PassesTheBoundBetweenSamplesByAtMostMuCh2Over20) {
  for (const ControlParams params : {figure_4_10_params(), ControlParams{0.4, 1.4135, 0.0156}}) {
    const double allowance =
        params.rate_per_s * params.max_speed * params.period_s * params.period_s / 20;
    for (const double velocity : {-0.4, 0.0, 0.3}) {
      for (const double target : {0.2, 0.45, 1.0, 5.0}) {
        const Trajectory run =
            simulate({0.0, velocity * params.max_speed}, params,
                     testing::steps_for(5.0 / (target * params.max_speed) + 4.0 / params.rate_per_s,
                                        params),
                     [&](const MotionState& state) {
                       return bounded_velocity_control(state, target * params.max_speed, -5.0,
                                                       5.0, params);
                     });
        for (std::size_t k = 0; k < run.controls.size(); ++k) {
          for (int j = 1; j < 50; ++j) {
            ASSERT_LE(closed_form(run.states[k], run.controls[k], params.rate_per_s,
                                  params.period_s * j / 50)
                          .position,
                      5.0 + allowance);
          }
        }
        EXPECT_NEAR(run.states.back().position, 5.0, 1e-12);
        EXPECT_NEAR(run.states.back().velocity, 0.0, 1e-12);
      }
    }
  }
}

// Without bounds (±∞) the law is exactly (4.14): 𝒞(v_d) = 𝒞(v_d, −∞, ∞).
TEST(BoundedVelocityControl, EqualsVelocityControlWithoutBounds) {
  const ControlParams params{0.4, 1.4135, 0.0156};
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < 10000; ++i) {
    const MotionState state{100 * unit(random), 1.5 * unit(random)};
    const double target = 2 * unit(random);
    ASSERT_EQ(bounded_velocity_control(state, target, -kInfinity, kInfinity, params),
              velocity_control(state.velocity, target, params));
  }
}

// Far from a bound the terms are ±C, as the thesis' 𝒞(0, p_min), 𝒞(0, p_max) are there.
TEST(BoundTerms, AreTheFullControlFarFromTheBound) {
  const ControlParams params{0.4, 1.4135, 0.0156};
  EXPECT_EQ(upper_bound_control({0.0, 1.0}, 5.0, params), params.max_speed);
  EXPECT_EQ(lower_bound_control({0.0, -1.0}, -5.0, params), -params.max_speed);
  EXPECT_EQ(upper_bound_control({0.0, 1.0}, kInfinity, params), params.max_speed);
  EXPECT_EQ(lower_bound_control({0.0, 1.0}, -kInfinity, params), -params.max_speed);
  // Beyond the bound, or unable to stop before it: back at full control.
  EXPECT_EQ(upper_bound_control({5.1, -1.0}, 5.0, params), -params.max_speed);
  EXPECT_EQ(lower_bound_control({-5.1, 1.0}, -5.0, params), params.max_speed);
}

TEST(BoundTerms, LowerIsTheMirroredUpper) {
  const ControlParams params{0.4, 1.4135, 0.0156};
  std::mt19937_64 random(19);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < 10000; ++i) {
    const MotionState state{unit(random), params.max_speed * unit(random)};
    const double bound = -1.0 + 0.5 * unit(random);
    ASSERT_EQ(lower_bound_control(state, bound, params),
              -upper_bound_control({-state.position, -state.velocity}, -bound, params));
  }
}

// The bounds hold as an invariant against any target: v_d jumps randomly in [−2C, 2C] every
// period, from states that can still stop inside, at 64 Hz and at a coarse hμ = 0.6.
TEST(BoundedVelocityControl, KeepsThePositionWithinTheBoundsForAnyTargetSequence) {
  for (const ControlParams params : {ControlParams{0.4, 1.4135, 0.0156},
                                     ControlParams{3.0, 1.0, 0.2}}) {
    std::mt19937_64 random(23);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const double low = -0.3;
    const double high = 0.4;
    for (int run = 0; run < 20; ++run) {
      MotionState state{0.05 * unit(random), 0.2 * params.max_speed * unit(random)};
      for (int k = 0; k < 5000; ++k) {
        const double target = 2 * params.max_speed * unit(random);
        const double control = bounded_velocity_control(state, target, low, high, params);
        ASSERT_LE(std::abs(control), params.max_speed);
        state = step(state, control, params);
        ASSERT_GE(state.position, low) << run << " " << k;
        ASSERT_LE(state.position, high) << run << " " << k;
      }
    }
  }
}

// A state beyond a bound is driven back inside and then kept there.
TEST(BoundedVelocityControl, ReturnsFromOutsideAndStaysInside) {
  const ControlParams params{0.4, 1.4135, 0.0156};
  const Trajectory run = simulate({2.7, 0.5}, params, testing::steps_for(20.0, params),
                                  [&](const MotionState& state) {
                                    return bounded_velocity_control(state, 1.0, 1.2121, 2.55,
                                                                    params);
                                  });
  EXPECT_EQ(run.controls.front(), -params.max_speed);
  bool inside = false;
  for (const MotionState& state : run.states) {
    inside = inside || state.position <= 2.55;
    if (inside) {
      ASSERT_LE(state.position, 2.55);
      ASSERT_GE(state.position, 1.2121);
    }
  }
  EXPECT_TRUE(inside);
  EXPECT_NEAR(run.states.back().position, 2.55, 1e-4);
}

// p_min = p_max = p_d is allowed. From below it stops exactly at p_d without ever passing it;
// (the upper term wins the clip, so from above it would first drop below: use (4.15) there).
TEST(BoundedVelocityControl, EqualBoundsAreReachedFromBelowWithoutPassing) {
  const ControlParams params{0.4, 1.4135, 0.0156};
  const Trajectory run = simulate({-1.2121, 0.0}, params, testing::steps_for(6.0, params),
                                  [&](const MotionState& state) {
                                    return bounded_velocity_control(state, 0.0, -0.21, -0.21,
                                                                    params);
                                  });
  for (const MotionState& state : run.states) {
    ASSERT_LE(state.position, -0.21);
  }
  EXPECT_NEAR(run.states.back().position, -0.21, 1e-12);
  EXPECT_NEAR(run.states.back().velocity, 0.0, 1e-12);
}

TEST(BoundedVelocityControl, RejectsInconsistentBounds) {
  const ControlParams params = figure_4_10_params();
  for (const auto& [low, high] : {std::pair{kNaN, 1.0}, std::pair{0.0, kNaN},
                                  std::pair{kInfinity, kInfinity}, std::pair{-kInfinity,
                                                                             -kInfinity},
                                  std::pair{2.0, 1.0}}) {
    expect_invalid_argument([&] { bounded_velocity_control({0, 0}, 0, low, high, params); },
                            {"bounded_velocity_control (4.16)", "min_position", "max_position"});
  }
  EXPECT_NO_THROW(bounded_velocity_control({0, 0}, 0, 1.0, 1.0, params));
  expect_invalid_argument([&] { upper_bound_control({0, 0}, -kInfinity, params); },
                          {"upper_bound_control", "max_position"});
  expect_invalid_argument([&] { lower_bound_control({0, 0}, kInfinity, params); },
                          {"lower_bound_control", "min_position"});
}

TEST(BoundedVelocityControl, RejectsNaNAndInfiniteInputsByName) {
  const ControlParams params = figure_4_10_params();
  for (const double bad : {kNaN, kInfinity, -kInfinity}) {
    expect_invalid_argument([&] { bounded_velocity_control({bad, 0}, 0, -1, 1, params); },
                            {"bounded_velocity_control (4.16)", "state.position"});
    expect_invalid_argument([&] { bounded_velocity_control({0, bad}, 0, -1, 1, params); },
                            {"state.velocity"});
    expect_invalid_argument([&] { bounded_velocity_control({0, 0}, bad, -1, 1, params); },
                            {"target_velocity"});
    expect_invalid_argument([&] { upper_bound_control({bad, 0}, 1, params); },
                            {"state.position"});
    expect_invalid_argument([&] { lower_bound_control({0, bad}, -1, params); },
                            {"state.velocity"});
  }
}

TEST(BoundedVelocityControl, NeverReturnsNaNOverARandomSweep) {
  const ControlParams params{0.4, 1.4135, 0.0156};
  std::mt19937_64 random(29);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < 20000; ++i) {
    const double scale = i % 10 == 0 ? 1e300 : 5.0;
    const double first = scale * unit(random);
    const double second = i % 7 == 0 ? first : scale * unit(random);
    const double velocity = i % 3 == 0 ? params.max_speed * (unit(random) > 0 ? 1 : -1)
                                       : 1.5 * params.max_speed * unit(random);
    const MotionState state{scale * unit(random), velocity};
    const double control = bounded_velocity_control(state, 2 * unit(random),
                                                    std::min(first, second),
                                                    std::max(first, second), params);
    ASSERT_TRUE(std::isfinite(control)) << i;
    ASSERT_LE(std::abs(control), params.max_speed) << i;
  }
}

}  // namespace
}  // namespace marsokhod::control
