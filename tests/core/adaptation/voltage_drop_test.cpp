#include "core/adaptation/voltage_drop.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "adaptation_test_util.hpp"

namespace marsokhod::adaptation {
namespace {

using test::invalid_argument_message;
using test::kNaN;
using ::testing::HasSubstr;

constexpr double kTolerance = 1e-12;

// ξ = 0.6 V, Ξ = 0.4 V s²/rad² (Field Experiment 4.11).
TEST(VoltageDrop, FullDutyWithoutLoadOnAllEightMotors) {
  const MotorVector duties{1, 1, 1, 1, 1, 1, 1, 1};
  EXPECT_NEAR(voltage_drop_v(duties, MotorVector{}, PowerParams{}), 0.6 * 8.0, kTolerance);
}

// Σ|d| = 0.5 + 0.5 + 0.3 + 0.3 + 1 + 1 = 3.6 → 0.6 · 3.6 = 2.16 V;
// Σl² = 0.25 + 0.25 + 1 = 1.5 rad²/s² → 0.4 · 1.5 = 0.6 V; together 2.76 V.
TEST(VoltageDrop, AddsTheDutyAndTheLoadTerms) {
  const MotorVector duties{0.5, -0.5, 0.3, -0.3, 0.0, 0.0, 1.0, -1.0};
  const MotorVector loads_radps{0.5, -0.5, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0};
  EXPECT_NEAR(voltage_drop_v(duties, loads_radps, PowerParams{}), 2.76, kTolerance);
  const MotorVector negated_duties{-0.5, 0.5, -0.3, 0.3, 0.0, 0.0, -1.0, 1.0};
  const MotorVector negated_loads_radps{-0.5, 0.5, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0};
  EXPECT_NEAR(voltage_drop_v(negated_duties, negated_loads_radps, PowerParams{}), 2.76, kTolerance);
}

// The two readings of Example 6.1 (docs/design.md): the unloaded duty D(0) that spends the whole
// budget Υ = 1.5 V is Υ/(nξ): 1.5/(6 · 0.6) = 0.41667 on six wheels, 1.5/(8 · 0.6) = 0.3125 on
// eight motors.
TEST(VoltageDrop, UnloadedDutyOfExample6_1SpendsTheWholeBudget) {
  const PowerParams power;
  const std::vector<double> six_wheels(6, power.max_drop_v / (6.0 * power.duty_drop_v));
  EXPECT_NEAR(voltage_drop_v(six_wheels, std::vector<double>(6, 0.0), power), 1.5, kTolerance);
  MotorVector eight_motors{};
  eight_motors.fill(0.3125);
  EXPECT_NEAR(voltage_drop_v(eight_motors, MotorVector{}, power), 1.5, kTolerance);
}

TEST(VoltageDrop, NothingRunningDropsNothing) {
  EXPECT_EQ(voltage_drop_v({}, {}, PowerParams{}), 0.0);
  EXPECT_EQ(voltage_drop_v(MotorVector{}, MotorVector{}, PowerParams{}), 0.0);
}

TEST(VoltageDrop, RejectsMismatchedOrInvalidInputsByName) {
  const std::vector<double> six(6, 0.1);
  const MotorVector eight{};
  EXPECT_THAT(invalid_argument_message([&] { voltage_drop_v(six, eight, PowerParams{}); }),
              HasSubstr("6 duties but 8 loads"));
  MotorVector duties{};
  duties[2] = 1.2;
  EXPECT_THAT(invalid_argument_message([&] { voltage_drop_v(duties, eight, PowerParams{}); }),
              HasSubstr("duties[2] = 1.2"));
  MotorVector loads_radps{};
  loads_radps[5] = kNaN;
  EXPECT_THAT(invalid_argument_message([&] { voltage_drop_v(eight, loads_radps, PowerParams{}); }),
              HasSubstr("loads_radps[5] = nan"));
  PowerParams power;
  power.load_drop_v_s2_per_rad2 = -0.4;
  EXPECT_THAT(invalid_argument_message([&] { voltage_drop_v(eight, eight, power); }),
              HasSubstr("power.load_drop_v_s2_per_rad2 = -0.4"));
  loads_radps[5] = 1e300;
  EXPECT_THAT(invalid_argument_message([&] { voltage_drop_v(eight, loads_radps, PowerParams{}); }),
              HasSubstr("overflowed"));
}

}  // namespace
}  // namespace marsokhod::adaptation
