#include "core/behaviour/power_management.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "behaviour_test_support.hpp"

namespace marsokhod::behaviour {
namespace {

using test::invalid_argument_message;
using test::kInf;
using test::kNaN;
using ::testing::HasSubstr;

constexpr double kTolerance = 1e-12;

// Example 6.1 as printed: Υ = 1.5, ξ = 0.6, D(0) = 0.417, D(0.2) = 0.4, D(0.5) = 0.375,
// D(1) = 0.333, D(2) = 0.25. These are (1.5 − 0.3 L)/(6 · 0.6) = (1.5 − 0.3 L)/3.6, i.e. six
// motors and Ξ = 0.3 (docs/design.md): 1.5/3.6 = 0.41667, 1.44/3.6 = 0.4, 1.35/3.6 = 0.375,
// 1.2/3.6 = 0.33333, 0.9/3.6 = 0.25.
TEST(PowerManagement, Example6_1WithSixMotorsAndXi0_3) {
  PowerParams power;
  power.load_drop_v_s2_per_rad2 = 0.3;
  EXPECT_NEAR(equal_duty_bound(0.0, 6, power), 1.5 / 3.6, kTolerance);
  EXPECT_NEAR(equal_duty_bound(0.0, 6, power), 0.417, 5e-4);
  EXPECT_NEAR(equal_duty_bound(0.2, 6, power), 0.4, kTolerance);
  EXPECT_NEAR(equal_duty_bound(0.5, 6, power), 0.375, kTolerance);
  EXPECT_NEAR(equal_duty_bound(1.0, 6, power), 0.333, 5e-4);
  EXPECT_NEAR(equal_duty_bound(2.0, 6, power), 0.25, kTolerance);
}

// The stated reading, 8 motors and Ξ = 0.4: (1.5 − 0.4 L)/4.8, so D(0) = 0.3125,
// D(0.2) = 1.42/4.8 = 0.295833, D(0.5) = 1.3/4.8 = 0.270833, D(1) = 1.1/4.8 = 0.229167,
// D(2) = 0.7/4.8 = 0.145833.
TEST(PowerManagement, Example6_1WithEightMotorsAndXi0_4) {
  const PowerParams power;
  EXPECT_NEAR(equal_duty_bound(0.0, 8, power), 0.3125, kTolerance);
  EXPECT_NEAR(equal_duty_bound(0.2, 8, power), 1.42 / 4.8, kTolerance);
  EXPECT_NEAR(equal_duty_bound(0.5, 8, power), 1.3 / 4.8, kTolerance);
  EXPECT_NEAR(equal_duty_bound(1.0, 8, power), 1.1 / 4.8, kTolerance);
  EXPECT_NEAR(equal_duty_bound(2.0, 8, power), 0.7 / 4.8, kTolerance);
}

// (6.1) is returned as printed: past L = Υ/Ξ = 3.75 the load alone exceeds the budget;
// D(5) = (1.5 − 2)/4.8 = −0.104167.
TEST(PowerManagement, EqualDutyBoundIsUnclamped) {
  EXPECT_NEAR(equal_duty_bound(5.0, 8, PowerParams{}), -0.5 / 4.8, kTolerance);
}

// All eight |d| = 0.5: max/Σ = 0.5/4 = 1/8, the factor of (6.1). Without load
// D = (1/8) · 1.5/0.6 = 0.3125; with l_i = ±0.25 on all eight, Σ l² = 0.5 and
// D = (1/8) · (1.5 − 0.2)/0.6 = 1.3/4.8 = 0.270833: (6.3) equals (6.1) with n = 8.
TEST(PowerManagement, EqualDutiesOnEightMotorsGiveTheFactorOneEighth) {
  const MotorVector duties{0.5, -0.5, 0.5, -0.5, 0.5, -0.5, 0.5, -0.5};
  const BehaviourSwitches on;
  EXPECT_NEAR(next_duty_bound(duties, MotorVector{}, PowerParams{}, on), 0.3125, kTolerance);
  const MotorVector loads_radps{0.25, -0.25, 0.25, -0.25, 0.25, -0.25, 0.25, -0.25};
  EXPECT_NEAR(next_duty_bound(duties, loads_radps, PowerParams{}, on), 1.3 / 4.8, kTolerance);
  EXPECT_NEAR(next_duty_bound(duties, loads_radps, PowerParams{}, on),
              equal_duty_bound(0.5, 8, PowerParams{}), kTolerance);
}

// Six wheels at |d| = 0.3, joints at rest: max/Σ = 0.3/1.8 = 1/6, D = 1.5/(6 · 0.6) = 0.41667,
// Example 6.1's D(0).
TEST(PowerManagement, SixEqualWheelDutiesGiveTheFactorOneSixth) {
  const MotorVector duties{0.3, 0.3, 0.3, 0.3, 0.3, 0.3, 0.0, 0.0};
  EXPECT_NEAR(next_duty_bound(duties, MotorVector{}, PowerParams{}, BehaviourSwitches{}), 1.5 / 3.6,
              kTolerance);
}

// d = (0.4, −0.4, 0.2, −0.2, 0, 0, 0, 0): max/Σ = 0.4/1.2 = 1/3; l = (−0.5, 0.5, 0, …):
// Σ l² = 0.5, budget 1.5 − 0.4 · 0.5 = 1.3 V; D = (1/3) · 1.3/0.6 = 0.722222.
TEST(PowerManagement, UnequalDutiesRaiseTheBound) {
  const MotorVector duties{0.4, -0.4, 0.2, -0.2, 0.0, 0.0, 0.0, 0.0};
  const MotorVector loads_radps{-0.5, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  EXPECT_NEAR(next_duty_bound(duties, loads_radps, PowerParams{}, BehaviourSwitches{}), 1.3 / 1.8,
              kTolerance);
}

// One motor alone: max/Σ = 1, 1.5/0.6 = 2.5 → min(2.5, 1) = 1.
TEST(PowerManagement, OneMotorAloneIsNotLimited) {
  const MotorVector duties{0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.3, 0.0};
  EXPECT_EQ(next_duty_bound(duties, MotorVector{}, PowerParams{}, BehaviourSwitches{}), 1.0);
}

// All d = 0: D = 1 whatever the loads (the "otherwise" of (6.3)).
TEST(PowerManagement, NoDutyGivesOne) {
  MotorVector loads_radps{};
  loads_radps.fill(3.0);
  EXPECT_EQ(next_duty_bound(MotorVector{}, loads_radps, PowerParams{}, BehaviourSwitches{}), 1.0);
}

// The bound spends exactly the budget: scaling the duties so that max|d| = D gives, by (4.5),
// ξ Σ|d| + Ξ Σ l² = ξ D Σ|d|/max|d| + Ξ L = Υ.
TEST(PowerManagement, ScalingTheDutiesToTheBoundDropsExactlyUpsilon) {
  const PowerParams power;
  const MotorVector duties{0.9, 0.7, -0.4, 0.2, 0.6, -0.8, 0.1, -0.05};
  const MotorVector loads_radps{-0.3, 0.2, -0.1, 0.4, 0.0, -0.2, 0.1, 0.0};
  const double bound = next_duty_bound(duties, loads_radps, power, BehaviourSwitches{});
  ASSERT_GT(bound, kMinimumDutyBound);
  ASSERT_LT(bound, 1.0);
  double drop_v = 0.0;
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    drop_v += power.duty_drop_v * std::abs(duties[i]) * bound / 0.9 +
              power.load_drop_v_s2_per_rad2 * loads_radps[i] * loads_radps[i];
  }
  EXPECT_NEAR(drop_v, power.max_drop_v, kTolerance);
}

// All |l| = 0.8: Ξ Σ l² = 0.4 · 8 · 0.64 = 2.048 V > Υ = 1.5 V, so (6.3) gives
// (1/8) · (−0.548)/0.6 = −0.114; the floor holds D at 0.05. Loads that overflow Σ l² too.
TEST(PowerManagement, AnOverspentBudgetGivesTheFloorNotZero) {
  const MotorVector duties{0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5};
  MotorVector loads_radps{};
  loads_radps.fill(-0.8);
  EXPECT_EQ(next_duty_bound(duties, loads_radps, PowerParams{}, BehaviourSwitches{}),
            kMinimumDutyBound);
  loads_radps.fill(1e200);
  EXPECT_EQ(next_duty_bound(duties, loads_radps, PowerParams{}, BehaviourSwitches{}),
            kMinimumDutyBound);
  PowerParams no_load_term;
  no_load_term.load_drop_v_s2_per_rad2 = 0.0;
  EXPECT_NEAR(next_duty_bound(duties, loads_radps, no_load_term, BehaviourSwitches{}), 0.3125,
              kTolerance);
}

TEST(PowerManagement, SwitchedOffGivesOne) {
  const MotorVector duties{0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5};
  EXPECT_EQ(next_duty_bound(duties, MotorVector{}, PowerParams{}, all_switched_off()), 1.0);
}

// Six wheels at d = 0.3 (max/Σ = 1/6) with 0.3 V of drop the model does not explain: the budget
// is 1.5 − 0.3 = 1.2 V, D = (1/6) · 1.2/0.6 = 1/3 instead of 0.41667.
TEST(PowerManagement, AnUnmodelledDropShrinksTheBudget) {
  const MotorVector duties{0.3, 0.3, 0.3, 0.3, 0.3, 0.3, 0.0, 0.0};
  EXPECT_NEAR(next_duty_bound(duties, MotorVector{}, PowerParams{}, BehaviourSwitches{}, 0.3),
              1.0 / 3.0, kTolerance);
  EXPECT_THAT(invalid_argument_message([&] {
                next_duty_bound(duties, MotorVector{}, PowerParams{}, BehaviourSwitches{}, -0.1);
              }),
              HasSubstr("unmodelled_drop_v = -0.1"));
}

// The excess of the measured over the modelled drop is taken at once and released with
// τ = 0.5 s: 0.4 V measured over 1.5 V modelled, then none: after 0.25 s (16 cycles of
// 15.625 ms) 0.4·e^(−0.5) = 0.24261 V. A model above the measurement gives no excess.
TEST(PowerManagement, MeasuredDropExcessAttacksAtOnceAndReleasesSlowly) {
  MeasuredDropExcess excess;
  EXPECT_DOUBLE_EQ(excess.update(1.2, 1.5, 0.015625), 0.0);
  EXPECT_NEAR(excess.update(1.9, 1.5, 0.015625), 0.4, kTolerance);
  for (int k = 0; k < 16; ++k) excess.update(1.0, 1.5, 0.015625);
  EXPECT_NEAR(excess.excess_v(), 0.4 * std::exp(-0.5), 1e-12);
  // A larger excess replaces the released one at once.
  EXPECT_NEAR(excess.update(2.0, 1.5, 0.015625), 0.5, kTolerance);
  EXPECT_THAT(invalid_argument_message([&] { excess.update(kNaN, 1.5, 0.015625); }),
              HasSubstr("measured_drop_v = nan"));
  EXPECT_THAT(invalid_argument_message([&] { excess.update(1.0, 1.5, 0.0); }),
              HasSubstr("period_s = 0"));
  EXPECT_NEAR(excess.excess_v(), 0.5, kTolerance);
}

TEST(PowerManagement, RejectsInvalidInputsByName) {
  const BehaviourSwitches on;
  MotorVector duties{};
  duties[3] = kNaN;
  EXPECT_THAT(
      invalid_argument_message([&] { next_duty_bound(duties, MotorVector{}, PowerParams{}, on); }),
      HasSubstr("next_duty_bound: duties[3] = nan"));
  duties[3] = 1.5;
  EXPECT_THAT(
      invalid_argument_message([&] { next_duty_bound(duties, MotorVector{}, PowerParams{}, on); }),
      HasSubstr("duties[3] = 1.5"));
  MotorVector loads_radps{};
  loads_radps[7] = kInf;
  EXPECT_THAT(invalid_argument_message(
                  [&] { next_duty_bound(MotorVector{}, loads_radps, PowerParams{}, on); }),
              HasSubstr("loads_radps[7] = inf"));
  PowerParams power;
  power.duty_drop_v = 0.0;
  EXPECT_THAT(
      invalid_argument_message([&] { next_duty_bound(MotorVector{}, MotorVector{}, power, on); }),
      HasSubstr("power.duty_drop_v = 0"));
  EXPECT_THAT(invalid_argument_message([] { equal_duty_bound(0.0, 0, PowerParams{}); }),
              HasSubstr("motor_count = 0"));
  EXPECT_THAT(invalid_argument_message([] { equal_duty_bound(-1.0, 8, PowerParams{}); }),
              HasSubstr("load_square_sum_rad2_per_s2 = -1"));
}

}  // namespace
}  // namespace marsokhod::behaviour
