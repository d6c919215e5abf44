#include "core/control/position_control.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "control_test_support.hpp"
#include "core/control/motion_model.hpp"

namespace marsokhod::control {
namespace {

using testing::expect_invalid_argument;
using testing::figure_4_10_params;
using testing::kInfinity;
using testing::kNaN;

Trajectory run_position_control(const MotionState& start, const MotionState& target,
                                const ControlParams& params, std::size_t steps) {
  return simulate(start, params, steps, [&](const MotionState& state) {
    return position_velocity_control(state, target, params);
  });
}

// Hand value (Figure 4.10, middle): v = −0.5 → v_d = 0.7 under c = +1, μ = 0.1:
// p_T = 0 + 10·(−0.5 − 0.7 + log(1.5/0.3)) = 10·(ln 5 − 1.2) = 4.0944 > p_d = 2, so c = −C.
TEST(PositionWhenVelocityReached, MatchesTheLemmaByHand) {
  const ControlParams params = figure_4_10_params();
  EXPECT_NEAR(position_when_velocity_reached({0.0, -0.5}, 0.7, params),
              10.0 * (std::log(5.0) - 1.2), 1e-12);
  EXPECT_EQ(bang_bang_position_velocity_control({0.0, -0.5}, {2.0, 0.7}, params), -1.0);
  EXPECT_EQ(position_velocity_control({0.0, -0.5}, {2.0, 0.7}, params), -1.0);
}

// p_T is where (4.10)/(4.11) under c = C·sgn(v_d − v) reach v_d, after T = log(…)/μ.
TEST(PositionWhenVelocityReached, AgreesWithTheClosedForm) {
  const ControlParams params{0.4, 1.4135, 0.0156};
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    const MotionState state{3 * unit(random), params.max_speed * unit(random)};
    const double target = 0.99 * params.max_speed * unit(random);
    const double control = state.velocity < target ? params.max_speed : -params.max_speed;
    const double reach_s =
        std::log((control - state.velocity) / (control - target)) / params.rate_per_s;
    const MotionState end = closed_form(state, control, params.rate_per_s, reach_s);
    ASSERT_NEAR(end.velocity, target, 1e-12);
    ASSERT_NEAR(position_when_velocity_reached(state, target, params), end.position, 1e-11);
  }
}

// The edges of the logarithm: v = v_d gives p_T = p (0·log 1); |v| > C counts as C; v_d at or
// beyond ±C is clamped strictly inside, so the result stays finite.
TEST(PositionWhenVelocityReached, HandlesTheEdgesOfTheLogarithm) {
  const ControlParams params = figure_4_10_params();
  EXPECT_EQ(position_when_velocity_reached({1.5, 0.3}, 0.3, params), 1.5);
  EXPECT_EQ(position_when_velocity_reached({1.5, 1.7}, -0.2, params),
            position_when_velocity_reached({1.5, 1.0}, -0.2, params));
  for (const double target : {1.0, -1.0, 5.0, -1e300}) {
    for (const double velocity : {1.0, -1.0, 0.0, target}) {
      EXPECT_TRUE(std::isfinite(position_when_velocity_reached({0.0, velocity}, target, params)))
          << velocity << " → " << target;
    }
  }
  EXPECT_EQ(bang_bang_position_velocity_control({2.0, 0.0}, {2.0, 0.0}, params), 0.0);
  EXPECT_EQ(position_velocity_control({2.0, 0.0}, {2.0, 0.0}, params), 0.0);
  EXPECT_EQ(position_velocity_control({2.0, 0.7}, {2.0, 0.7}, params), 0.7);
}

// Figure 4.10, middle: v0 = −0.5, p0 = 0 → (v_d, p_d) = (0.7, 2), μ = 0.1, C = 1, h = 0.0156 s.
// Lemma 4.15: −C for t1 = 2.900 s, then +C until v = 0.7 at p = 2, T* = 19.800 s (found here by
// scanning one-switch controls in closed form). The sampled state passes through the target:
// it is "reached" within one period's travel |v_d|·h = 0.0109 and one period's full
// acceleration 2μC·h = 0.0031, within two periods of T*, with |v| ≤ C all along.
TEST(PositionVelocityControl, Figure410PositionCaseReachesTheTargetInLeastTime) {
  const ControlParams params = figure_4_10_params();
  const MotionState start{0.0, -0.5};
  const MotionState target{2.0, 0.7};
  const double best_s = testing::best_one_switch_time(start, target, params.rate_per_s,
                                                      params.max_speed, 0.01, 40.0);
  ASSERT_NEAR(best_s, 19.8004, 1e-4);
  const Trajectory run =
      run_position_control(start, target, params, testing::steps_for(25.0, params));
  const auto reached = testing::first_reach(
      run, target, target.velocity * params.period_s,
      2 * params.rate_per_s * params.max_speed * params.period_s);
  ASSERT_TRUE(reached.has_value());
  const double reached_s = static_cast<double>(*reached) * params.period_s;
  EXPECT_GE(reached_s, best_s - params.period_s);
  EXPECT_LE(reached_s, best_s + 2 * params.period_s);
  int switches = 0;
  for (std::size_t k = 0; k < *reached; ++k) {
    ASSERT_LE(std::abs(run.states[k].velocity), params.max_speed);
    if (k > 0 && run.controls[k] * run.controls[k - 1] < 0.0) {
      ++switches;
    }
  }
  EXPECT_EQ(run.controls.front(), -1.0);
  EXPECT_EQ(switches, 1);  // one switch, as the lemma says
}

// Time-optimality as a property. On a grid of start states and targets (μ = 1, C = 1,
// h = 0.01 s), the sampled law reaches the target no later than two periods after the fastest
// one-switch control in continuous time (scanned in closed form, no use of p_T) — two periods
// being the terminal two-step solution — and never earlier, since no control beats the lemma;
// and like the lemma's control it switches between +C and −C at most once. v_d = 0 targets
// are reached exactly (1e-9); v_d ≠ 0 ones are passed through within |v_d|·h and 2μC·h as in
// Figure 4.10, a box the state may enter up to a period before the target itself.
TEST(PositionVelocityControl, IsNoSlowerThanAnyOneSwitchControlUpToTwoPeriods) {
  const ControlParams params{1.0, 1.0, 0.01};
  const double period = params.period_s;
  for (const double target_velocity : {0.0, 0.5, -0.3}) {
    for (const double velocity : {-0.9, -0.4, 0.0, 0.4, 0.9}) {
      for (const double position : {-3.0, -1.0, -0.2, 0.2, 1.0, 3.0}) {
        const MotionState start{position, velocity};
        const MotionState target{0.0, target_velocity};
        const double best_s =
            testing::best_one_switch_time(start, target, 1.0, 1.0, period / 10, 8.0);
        ASSERT_LT(best_s, 8.0);
        const Trajectory run = run_position_control(start, target, params, 900);
        const bool at_rest = target_velocity == 0.0;
        const auto reached = testing::first_reach(
            run, target, at_rest ? 1e-9 : std::abs(target_velocity) * period,
            at_rest ? 1e-9 : 2 * params.rate_per_s * params.max_speed * period);
        ASSERT_TRUE(reached.has_value()) << velocity << ", " << position << " → "
                                         << target_velocity;
        const double reached_s = static_cast<double>(*reached) * period;
        EXPECT_LE(reached_s, best_s + 2 * period)
            << velocity << ", " << position << " → " << target_velocity;
        EXPECT_GE(reached_s, best_s - (at_rest ? 0.0 : period))
            << velocity << ", " << position << " → " << target_velocity;
        int switches = 0;  // between the saturated controls ±C: at most one, as in the lemma
        double last_saturated = 0.0;
        for (std::size_t k = 0; k < *reached; ++k) {
          if (std::abs(run.controls[k]) == params.max_speed) {
            switches += run.controls[k] * last_saturated < 0.0 ? 1 : 0;
            last_saturated = run.controls[k];
          }
        }
        EXPECT_LE(switches, 1) << velocity << ", " << position << " → " << target_velocity;
      }
    }
  }
}

// Holding a target at rest: once reached the state stays there with c = 0 (to rounding), whereas
// the thesis' sign law as printed keeps switching between ±C around it (chatter).
TEST(PositionVelocityControl, SettlesWhereThePrintedSignLawChatters) {
  const ControlParams params{0.4, 1.4135, 0.0156};
  const MotionState start{-1.2121, 0.0};
  const MotionState target{-2.21, 0.0};
  const std::size_t steps = testing::steps_for(8.0, params);
  const Trajectory ours = run_position_control(start, target, params, steps);
  const Trajectory printed = simulate(start, params, steps, [&](const MotionState& state) {
    return bang_bang_position_velocity_control(state, target, params);
  });
  int printed_switches = 0;
  for (std::size_t k = steps - testing::steps_for(1.0, params); k < steps; ++k) {
    EXPECT_NEAR(ours.controls[k], 0.0, 1e-12);
    EXPECT_NEAR(ours.states[k].position, target.position, 1e-12);
    EXPECT_NEAR(ours.states[k].velocity, 0.0, 1e-12);
    EXPECT_EQ(std::abs(printed.controls[k]), params.max_speed);
    printed_switches += printed.controls[k] * printed.controls[k - 1] < 0.0 ? 1 : 0;
  }
  EXPECT_GE(printed_switches, 8);
}

// Procedure 4.17 on the model only (no rover, no backlash): μ = 0.4, C = w/2 = 1.4135 rad/s,
// h = 0.0156 s, v_d = 0. The next target is assigned once |p − p_d| ≤ 0.05 rad held for 1 s
// (65 periods). Each target must be reached within 1 s plus two periods of the least time of
// Lemma 4.15, stopped (|v| ≤ 1e-9) and exactly on target at the hand-over, never passed by more
// than the μC·h²/16 of the terminal step, and |v| ≤ C throughout.
void run_procedure_4_17(double start_rad, const std::vector<double>& targets_rad) {
  const ControlParams params = joint_control_params(Params{});
  const double tolerance_rad = Params{}.joints.target_tolerance_rad;
  const std::size_t hold_steps = testing::steps_for(1.0, params);
  const StepCoefficients coefficients = step_coefficients(params);
  MotionState state{start_rad, 0.0};
  for (const double target_rad : targets_rad) {
    const MotionState target{target_rad, 0.0};
    const double best_s = testing::best_one_switch_time(state, target, params.rate_per_s,
                                                        params.max_speed, 0.001, 10.0);
    const double direction = target_rad > state.position ? 1.0 : -1.0;
    std::size_t held = 0;
    std::size_t k = 0;
    for (; held < hold_steps && k < 2000; ++k) {
      const double control = position_velocity_control(state, target, params);
      ASSERT_LE(std::abs(control), params.max_speed);
      state = step(state, control, coefficients);
      ASSERT_LE(std::abs(state.velocity), params.max_speed);
      ASSERT_LE(direction * (state.position - target_rad), 1e-5) << "passed " << target_rad;
      held = std::abs(state.position - target_rad) <= tolerance_rad ? held + 1 : 0;
    }
    ASSERT_EQ(held, hold_steps) << "never held " << target_rad;
    EXPECT_LE(static_cast<double>(k) * params.period_s, best_s + 1.0 + 3 * params.period_s)
        << target_rad;
    EXPECT_NEAR(state.position, target_rad, 1e-9);
    EXPECT_NEAR(state.velocity, 0.0, 1e-9);
  }
}

TEST(PositionVelocityControl, Procedure417FrontJointSequence) {
  run_procedure_4_17(-1.2121, {-2.21, -2.51, -1.61, -1.81, -1.21});
}

TEST(PositionVelocityControl, Procedure417RearJointSequence) {
  run_procedure_4_17(1.2121, {2.21, 2.51, 1.61, 1.81, 1.21});
}

// No NaN and |c| ≤ C on a random sweep that includes the edges of the logarithm: |v| = C,
// v = v_d, |v_d| ≥ C, |v| > C, exact targets, and huge magnitudes.
TEST(PositionVelocityControl, NeverReturnsNaNOverARandomSweepIncludingTheEdges) {
  const ControlParams params{0.4, 1.4135, 0.0156};
  const double speed = params.max_speed;
  std::mt19937_64 random(13);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> pick(0, 7);
  for (int i = 0; i < 20000; ++i) {
    const double scale = i % 10 == 0 ? 1e300 : 5.0;
    const MotionState target{scale * unit(random),
                             pick(random) == 0 ? speed * (unit(random) > 0 ? 1 : -1)
                                               : 1.5 * speed * unit(random)};
    double velocity = 1.2 * speed * unit(random);
    switch (pick(random)) {
      case 0: velocity = speed; break;
      case 1: velocity = -speed; break;
      case 2: velocity = target.velocity; break;
      default: break;
    }
    const MotionState state{pick(random) == 0 ? target.position : scale * unit(random), velocity};
    const double control = position_velocity_control(state, target, params);
    ASSERT_TRUE(std::isfinite(control)) << i;
    ASSERT_LE(std::abs(control), speed) << i;
    ASSERT_LE(std::abs(bang_bang_position_velocity_control(state, target, params)), speed);
    ASSERT_FALSE(std::isnan(position_when_velocity_reached(state, target.velocity, params)));
  }
}

TEST(PositionVelocityControl, RejectsNaNAndInfiniteInputsByName) {
  const ControlParams params = figure_4_10_params();
  for (const double bad : {kNaN, kInfinity, -kInfinity}) {
    expect_invalid_argument([&] { position_velocity_control({bad, 0}, {1, 0}, params); },
                            {"position_velocity_control (4.15)", "state.position"});
    expect_invalid_argument([&] { position_velocity_control({0, bad}, {1, 0}, params); },
                            {"state.velocity"});
    expect_invalid_argument([&] { position_velocity_control({0, 0}, {bad, 0}, params); },
                            {"target.position"});
    expect_invalid_argument([&] { position_velocity_control({0, 0}, {1, bad}, params); },
                            {"target.velocity"});
    expect_invalid_argument([&] { bang_bang_position_velocity_control({bad, 0}, {1, 0}, params); },
                            {"state.position"});
    expect_invalid_argument([&] { position_when_velocity_reached({0, 0}, bad, params); },
                            {"target.velocity"});
  }
  expect_invalid_argument([] { position_velocity_control({0, 0}, {1, 0}, ControlParams{}); },
                          {"ControlParams"});
}

}  // namespace
}  // namespace marsokhod::control
