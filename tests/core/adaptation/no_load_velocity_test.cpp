#include "core/adaptation/no_load_velocity.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "adaptation_test_util.hpp"

namespace marsokhod::adaptation {
namespace {

using test::invalid_argument_message;
using test::kInf;
using test::kNaN;
using ::testing::HasSubstr;

constexpr double kNominalSupplyV = 24.0;  // Ū
constexpr double kZeta3 = 0.941;          // ζ3, the center-right wheel (Procedure 4.5)

MotorCurve default_curve() { return MotorCurve(Params{}.motor_curves.at(0)); }

double round_to(double value, int digits) {
  const double scale = std::pow(10.0, digits);
  return std::round(value * scale) / scale;
}

// Example 4.6, first half: ŵ = 0.941 · 0.847 · 22/24 = 0.797027 · 0.916667 = 0.730608 → 0.731.
TEST(NoLoadVelocity, Example4_6CenterRightWheelAtThirtyPercentAndTwentyTwoVolts) {
  const double w_hat_radps = no_load_velocity(default_curve(), 0.3, kZeta3, 22.0, kNominalSupplyV);
  EXPECT_NEAR(w_hat_radps, 0.941 * 0.847 * 22.0 / 24.0, 1e-12);
  EXPECT_EQ(round_to(w_hat_radps, 3), 0.731);
}

// Example 4.6, second half: at U = 21 V, ŵ = −2 rad/s needs
//   d = W⁻¹(−2/0.941 · 24/21) = W⁻¹(−2.429027) = −(0.8 + 0.1 · 0.059027/0.23) = −0.825664.
// The thesis prints "= 0.826": after "= −W⁻¹(2.429)" the minus sign got lost. A negative
// velocity needs a negative duty, so −0.826 is right (within ±0.005 of the reconstructed W).
TEST(NoLoadVelocity, Example4_6DutyForMinusTwoRadPerSecondAtTwentyOneVolts) {
  const MotorCurve curve = default_curve();
  const double duty = duty_for_no_load_velocity(curve, -2.0, kZeta3, 21.0, kNominalSupplyV);
  const double argument_radps = -2.0 / 0.941 * 24.0 / 21.0;
  EXPECT_NEAR(argument_radps, -2.429, 0.0005);
  EXPECT_NEAR(duty, -(0.8 + 0.1 * (-argument_radps - 2.37) / 0.23), 1e-12);
  EXPECT_NEAR(duty, -0.826, 0.005);
}

TEST(NoLoadVelocity, DutyAndVelocityAreInversesAtAnySupply) {
  const MotorCurve curve = default_curve();
  for (const double supply_v : {16.0, 20.0, 22.0, 24.0, 25.5}) {
    for (int i = -100; i <= 100; ++i) {
      const double duty = i / 100.0;
      const double w_hat_radps = no_load_velocity(curve, duty, kZeta3, supply_v, kNominalSupplyV);
      ASSERT_NEAR(duty_for_no_load_velocity(curve, w_hat_radps, kZeta3, supply_v, kNominalSupplyV),
                  duty, 1e-12)
          << "U = " << supply_v << ", d = " << duty;
    }
  }
}

// Full duty at 21 V gives ζ3 · 2.827 · 21/24 = 2.3276 rad/s; asking for more saturates at ±1.
TEST(NoLoadVelocity, DutySaturatesWhenTheSupplyCannotDeliver) {
  const MotorCurve curve = default_curve();
  EXPECT_EQ(duty_for_no_load_velocity(curve, 2.4, kZeta3, 21.0, kNominalSupplyV), 1.0);
  EXPECT_EQ(duty_for_no_load_velocity(curve, -2.4, kZeta3, 21.0, kNominalSupplyV), -1.0);
  EXPECT_NEAR(no_load_velocity(curve, 1.2, kZeta3, 21.0, kNominalSupplyV),
              0.941 * 2.827 * 21.0 / 24.0, 1e-12);
  // A denormal ζ overflows the quotient; the duty still saturates instead of passing inf on.
  EXPECT_EQ(duty_for_no_load_velocity(curve, 1.0, 1e-320, 24.0, kNominalSupplyV), 1.0);
}

// Remark 4.7: the wheel of Example 4.6 measured at 0.730608 rad/s, 22 V, is left at d = 0.3.
TEST(PassiveDuty, PicksUpTheAmbientSpeed) {
  const MotorCurve curve = default_curve();
  const double measured_radps = 0.941 * 0.847 * 22.0 / 24.0;
  EXPECT_NEAR(passive_duty(curve, measured_radps, kZeta3, 22.0, kNominalSupplyV), 0.3, 1e-12);
  EXPECT_NEAR(passive_duty(curve, -measured_radps, kZeta3, 22.0, kNominalSupplyV), -0.3, 1e-12);
  EXPECT_EQ(passive_duty(curve, 0.0, kZeta3, 22.0, kNominalSupplyV), 0.0);
  EXPECT_EQ(passive_duty(curve, 10.0, kZeta3, 22.0, kNominalSupplyV), 1.0);
}

TEST(NoLoadVelocity, RejectsNonFiniteAndNonPositiveArgumentsByName) {
  const MotorCurve curve = default_curve();
  EXPECT_THAT(invalid_argument_message([&] { no_load_velocity(curve, kNaN, 1.0, 24.0, 24.0); }),
              HasSubstr("no_load_velocity: duty = nan"));
  EXPECT_THAT(invalid_argument_message([&] { no_load_velocity(curve, 0.3, 0.0, 24.0, 24.0); }),
              HasSubstr("zeta = 0"));
  EXPECT_THAT(
      invalid_argument_message([&] { duty_for_no_load_velocity(curve, 1.0, 1.0, kNaN, 24.0); }),
      HasSubstr("duty_for_no_load_velocity: supply_v = nan"));
  EXPECT_THAT(
      invalid_argument_message([&] { duty_for_no_load_velocity(curve, kInf, 1.0, 24.0, 24.0); }),
      HasSubstr("w_hat_radps = inf"));
  EXPECT_THAT(invalid_argument_message([&] { passive_duty(curve, 1.0, 1.0, 24.0, -24.0); }),
              HasSubstr("passive_duty: nominal_supply_v = -24"));
  EXPECT_THAT(invalid_argument_message([&] { passive_duty(curve, kNaN, 1.0, 24.0, 24.0); }),
              HasSubstr("measured_velocity_radps = nan"));
  EXPECT_THAT(invalid_argument_message([&] { no_load_velocity(curve, 1.0, 1e300, 1e300, 1e-300); }),
              HasSubstr("overflowed"));
}

}  // namespace
}  // namespace marsokhod::adaptation
