#include "core/control/motion_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "control_test_support.hpp"

namespace marsokhod::control {
namespace {

using testing::expect_invalid_argument;
using testing::kInfinity;
using testing::kNaN;

// Hand values: from rest with c = 1, μ = 0.1 after t = 10 s (tμ = 1):
// v = 1 − e^(−1), p = (1/μ)(tμ − 1 + e^(−1)) = 10·e^(−1).
TEST(ClosedForm, MatchesHandValuesOfFormulas410And411) {
  const MotionState state = closed_form({0.0, 0.0}, 1.0, 0.1, 10.0);
  EXPECT_NEAR(state.velocity, 1.0 - std::exp(-1.0), 1e-15);
  EXPECT_NEAR(state.position, 10.0 * std::exp(-1.0), 1e-14);
  // v0 alone: p = p0 + (v0/μ)(1 − e^(−1)), v = v0·e^(−1).
  const MotionState coasting = closed_form({2.0, 0.5}, 0.0, 0.1, 10.0);
  EXPECT_NEAR(coasting.velocity, 0.5 * std::exp(-1.0), 1e-15);
  EXPECT_NEAR(coasting.position, 2.0 + 5.0 * (1.0 - std::exp(-1.0)), 1e-14);
}

TEST(ClosedForm, StartsAtTheInitialStateAndSettlesAtTheControl) {
  const MotionState start{-1.2121, 0.3};
  const MotionState now = closed_form(start, -0.7, 0.4, 0.0);
  EXPECT_EQ(now.position, start.position);
  EXPECT_EQ(now.velocity, start.velocity);
  EXPECT_NEAR(closed_form(start, -0.7, 0.4, 200.0).velocity, -0.7, 1e-12);
}

// (4.8)/(4.9) hold along (4.10)/(4.11): central differences of the closed form.
TEST(ClosedForm, SolvesTheDifferentialEquations48And49) {
  const MotionState start{0.5, -0.8};
  const double rate = 0.4;
  const double control = 1.0;
  const double delta = 1e-5;
  for (const double t : {0.01, 0.7, 3.0, 12.0}) {
    const MotionState before = closed_form(start, control, rate, t - delta);
    const MotionState here = closed_form(start, control, rate, t);
    const MotionState after = closed_form(start, control, rate, t + delta);
    EXPECT_NEAR((after.position - before.position) / (2 * delta), here.velocity, 1e-8);
    EXPECT_NEAR((after.velocity - before.velocity) / (2 * delta),
                rate * (control - here.velocity), 1e-8);
  }
}

// (4.12)/(4.13) are exact: n steps of constant c equal the closed form at t = n·h to 1e-12
// (relative to max(1, |p|)) over 10000 steps, at the thesis' 64 Hz and at a coarse hμ.
TEST(Step, AgreesWithTheClosedFormForConstantControlOverManySteps) {
  for (const ControlParams params : {ControlParams{0.1, 1.0, 0.0156},
                                     ControlParams{0.4, 1.4135, 0.0156},
                                     ControlParams{10.0, 2.0, 0.05}}) {
    for (const double fraction : {-1.0, 0.0, 0.37, 1.0}) {
      const double control = fraction * params.max_speed;
      const MotionState start{1.2, -0.3 * params.max_speed};
      const Trajectory run =
          simulate(start, params, 10000, [&](const MotionState&) { return control; });
      for (std::size_t k = 0; k < run.states.size(); k += 97) {
        const MotionState exact = closed_form(start, control, params.rate_per_s,
                                              static_cast<double>(k) * params.period_s);
        const double scale = std::max(1.0, std::abs(exact.position));
        ASSERT_NEAR(run.states[k].position, exact.position, 1e-12 * scale) << k;
        ASSERT_NEAR(run.states[k].velocity, exact.velocity, 1e-12) << k;
      }
    }
  }
}

// The c-coefficient (hμ − 1 + e^(−hμ))/μ = μh²/2·(1 − hμ/3 + (hμ)²/12 − …) keeps full precision
// for small hμ, and the series and the direct formula meet at hμ = 0.1.
TEST(StepCoefficients, KeepPrecisionForSmallPeriods) {
  const double rate = 1.0;
  for (const double period : {1e-8, 1e-5, 0.00624}) {
    const StepCoefficients k = step_coefficients({rate, 1.0, period});
    const double x = period * rate;
    const double expected =
        x * x / 2 * (1 - x / 3 + x * x / 12 - x * x * x / 60 + x * x * x * x / 360);
    EXPECT_NEAR(k.position_per_control_s / expected, 1.0, 1e-13) << period;
  }
  const double below = step_coefficients({1.0, 1.0, std::nextafter(0.1, 0.0)})
                           .position_per_control_s;
  const double above = step_coefficients({1.0, 1.0, 0.1}).position_per_control_s;
  EXPECT_NEAR(below / above, 1.0, 1e-14);
}

// The model is odd in (p, v, c), bit for bit; lower_bound_control relies on it.
TEST(Step, IsExactlyOddInStateAndControl) {
  const StepCoefficients k = step_coefficients({0.4, 1.4135, 0.0156});
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> any(-3.0, 3.0);
  for (int i = 0; i < 1000; ++i) {
    const MotionState state{any(random), any(random)};
    const double control = any(random);
    const MotionState forward = step(state, control, k);
    const MotionState mirrored = step({-state.position, -state.velocity}, -control, k);
    ASSERT_EQ(mirrored.position, -forward.position);
    ASSERT_EQ(mirrored.velocity, -forward.velocity);
  }
}

// v' is a convex combination of v and c: |v| ≤ C and |c| ≤ C keep |v'| ≤ C (up to rounding).
TEST(Step, KeepsTheVelocityWithinTheControlBound) {
  const ControlParams params{0.4, 1.4135, 0.0156};
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  MotionState state{0.0, params.max_speed};
  for (int i = 0; i < 100000; ++i) {
    const double control = (i % 3 == 0 ? (unit(random) > 0 ? 1.0 : -1.0) : unit(random)) *
                           params.max_speed;
    state = step(state, control, params);
    ASSERT_LE(std::abs(state.velocity), params.max_speed * (1 + 1e-15)) << i;
  }
}

// Two periods of the exact controls land on the target (to rounding); targets out of reach
// of |c| ≤ C in two periods give none.
TEST(TwoStepControls, ReachTheTargetExactlyInTwoPeriods) {
  const StepCoefficients k = step_coefficients({0.4, 1.4135, 0.0156});
  std::mt19937_64 random(31);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int reachable = 0;
  for (int i = 0; i < 1000; ++i) {
    const MotionState state{unit(random), unit(random)};
    const MotionState target{state.position + 0.0312 * state.velocity + 1e-4 * unit(random),
                             state.velocity + 0.01 * unit(random)};
    const auto controls = two_step_controls(state, target, 1e9, k);
    ASSERT_TRUE(controls.has_value());
    const MotionState end = step(step(state, controls->first, k), controls->second, k);
    ASSERT_NEAR(end.position, target.position, 1e-12);
    ASSERT_NEAR(end.velocity, target.velocity, 1e-12);
    reachable += two_step_controls(state, target, 1.4135, k).has_value() ? 1 : 0;
  }
  EXPECT_GT(reachable, 0);
  EXPECT_LT(reachable, 1000);
  const auto stay = two_step_controls({2.0, 0.0}, {2.0, 0.0}, 1.0, k);
  ASSERT_TRUE(stay.has_value());
  EXPECT_EQ(stay->first, 0.0);
  EXPECT_EQ(stay->second, 0.0);
  EXPECT_FALSE(two_step_controls({0.0, 0.0}, {1.0, 0.0}, 1.0, k).has_value());
  EXPECT_FALSE(two_step_controls({-1e300, 0.0}, {1e300, 0.0}, 1.0, k).has_value());
  expect_invalid_argument([&] { two_step_controls({kNaN, 0.0}, {0.0, 0.0}, 1.0, k); },
                          {"two_step_controls", "state.position"});
  expect_invalid_argument([&] { two_step_controls({0.0, 0.0}, {0.0, kInfinity}, 1.0, k); },
                          {"target.velocity"});
}

TEST(Simulate, RecordsEveryStateAndControl) {
  const ControlParams params = testing::figure_4_10_params();
  std::size_t calls = 0;
  const Trajectory run = simulate({1.0, 0.0}, params, 5, [&](const MotionState& state) {
    ++calls;
    return state.velocity > 0.5 ? -1.0 : 1.0;
  });
  EXPECT_EQ(calls, 5u);
  ASSERT_EQ(run.states.size(), 6u);
  ASSERT_EQ(run.controls.size(), 5u);
  EXPECT_EQ(run.states.front().position, 1.0);
  for (std::size_t k = 0; k < 5; ++k) {
    const MotionState next = step(run.states[k], run.controls[k], params);
    EXPECT_EQ(run.states[k + 1].position, next.position);
    EXPECT_EQ(run.states[k + 1].velocity, next.velocity);
  }
}

TEST(Simulate, RejectsALawThatReturnsNaNOrLeavesTheBound) {
  const ControlParams params = testing::figure_4_10_params();
  expect_invalid_argument(
      [&] { simulate({0, 0}, params, 3, [](const MotionState&) { return kNaN; }); },
      {"simulate", "control"});
  expect_invalid_argument(
      [&] { simulate({0, 0}, params, 3, [](const MotionState&) { return 1.0000001; }); },
      {"simulate", "|c| ≤ C"});
  EXPECT_NO_THROW(simulate({0, 0}, params, 3, [](const MotionState&) { return -1.0; }));
  expect_invalid_argument(
      [&] { simulate({kNaN, 0}, params, 3, [](const MotionState&) { return 0.0; }); },
      {"initial.position"});
}

TEST(MotionModel, RejectsNaNAndInfiniteInputsByName) {
  const ControlParams params = testing::figure_4_10_params();
  for (const double bad : {kNaN, kInfinity, -kInfinity}) {
    expect_invalid_argument([&] { closed_form({bad, 0}, 0, 0.1, 1); }, {"initial.position"});
    expect_invalid_argument([&] { closed_form({0, bad}, 0, 0.1, 1); }, {"initial.velocity"});
    expect_invalid_argument([&] { closed_form({0, 0}, bad, 0.1, 1); }, {"control"});
    expect_invalid_argument([&] { closed_form({0, 0}, 0, bad, 1); }, {"rate_per_s"});
    expect_invalid_argument([&] { closed_form({0, 0}, 0, 0.1, bad); }, {"t_s"});
    expect_invalid_argument([&] { step({bad, 0}, 0, params); }, {"state.position"});
    expect_invalid_argument([&] { step({0, bad}, 0, params); }, {"state.velocity"});
    expect_invalid_argument([&] { step({0, 0}, bad, params); }, {"control"});
  }
  expect_invalid_argument([] { closed_form({0, 0}, 0, 0.1, -1.0); }, {"t_s", "≥ 0"});
  expect_invalid_argument([] { step({0, 0}, 0, ControlParams{}); }, {"ControlParams"});
}

}  // namespace
}  // namespace marsokhod::control
