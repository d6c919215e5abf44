#include "core/adaptation/motor_curve.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "adaptation_test_util.hpp"

namespace marsokhod::adaptation {
namespace {

using test::invalid_argument_message;
using test::kInf;
using test::kNaN;
using ::testing::HasSubstr;

// W₅₁₁ of Params: d = 0, 0.1, …, 1 → 0, 0.19, 0.52, 0.847, 1.18, 1.50, 1.81, 2.10, 2.37, 2.60,
// 2.827 rad/s.
MotorCurve default_curve() { return MotorCurve(Params{}.motor_curves.at(0)); }

TEST(MotorCurve, HitsTheThesisAnchorsAtTheNodes) {
  const MotorCurve curve = default_curve();
  EXPECT_EQ(curve.icr(), 511);
  EXPECT_EQ(curve.velocity_radps(0.3), 0.847);  // Example 4.6: W₅₁₁(0.3) = 0.847
  EXPECT_EQ(curve.velocity_radps(1.0), 2.827);  // W(1) = w
  EXPECT_EQ(curve.velocity_radps(0.0), 0.0);
  EXPECT_EQ(curve.max_velocity_radps(), 2.827);
  EXPECT_EQ(curve.duty(0.847), 0.3);
  EXPECT_EQ(curve.duty(2.827), 1.0);
}

// Between the nodes: W(0.35) = 0.847 + ½ (1.18 − 0.847) = 1.0135;
// W⁻¹(2.429) = 0.8 + 0.1 (2.429 − 2.37)/(2.60 − 2.37) = 0.8 + 0.059/2.3 = 0.825652…
TEST(MotorCurve, InterpolatesLinearlyBetweenNodes) {
  const MotorCurve curve = default_curve();
  EXPECT_NEAR(curve.velocity_radps(0.35), 1.0135, 1e-12);
  EXPECT_NEAR(curve.duty(2.429), 0.8 + 0.059 / 2.3, 1e-12);
}

TEST(MotorCurve, IsOdd) {
  const MotorCurve curve = default_curve();
  for (double duty = 0.0; duty <= 1.2; duty += 0.0137) {
    EXPECT_EQ(curve.velocity_radps(-duty), -curve.velocity_radps(duty)) << duty;
  }
  for (double velocity = 0.0; velocity <= 3.0; velocity += 0.0371) {
    EXPECT_EQ(curve.duty(-velocity), -curve.duty(velocity)) << velocity;
  }
}

TEST(MotorCurve, SaturatesBeyondFullDutyAndFullSpeed) {
  const MotorCurve curve = default_curve();
  EXPECT_EQ(curve.velocity_radps(1.5), 2.827);
  EXPECT_EQ(curve.velocity_radps(-7.0), -2.827);
  EXPECT_EQ(curve.duty(3.0), 1.0);
  EXPECT_EQ(curve.duty(-2.9), -1.0);
}

TEST(MotorCurve, InverseUndoesTheCurveOnAFineGrid) {
  const MotorCurve curve = default_curve();
  for (int i = -10000; i <= 10000; ++i) {
    const double duty = i / 10000.0;
    ASSERT_NEAR(curve.duty(curve.velocity_radps(duty)), duty, 1e-12) << duty;
  }
  for (int i = -10000; i <= 10000; ++i) {
    const double velocity_radps = 2.827 * i / 10000.0;
    ASSERT_NEAR(curve.velocity_radps(curve.duty(velocity_radps)), velocity_radps, 1e-12)
        << velocity_radps;
  }
}

TEST(MotorCurve, IsMonotoneAlsoInFloatingPoint) {
  const MotorCurve curve = default_curve();
  double previous_velocity = -kInf;
  double previous_duty = -kInf;
  for (int i = -12000; i <= 12000; ++i) {
    const double velocity = curve.velocity_radps(i / 10000.0);
    const double duty = curve.duty(3.0 * i / 12000.0);
    ASSERT_GE(velocity, previous_velocity) << i;
    ASSERT_GE(duty, previous_duty) << i;
    previous_velocity = velocity;
    previous_duty = duty;
  }
}

TEST(MotorCurve, RejectsNonFiniteArguments) {
  const MotorCurve curve = default_curve();
  EXPECT_THAT(invalid_argument_message([&] { curve.velocity_radps(kNaN); }),
              HasSubstr("MotorCurve::velocity_radps: duty = nan"));
  EXPECT_THAT(invalid_argument_message([&] { curve.duty(-kInf); }),
              HasSubstr("velocity_radps = -inf"));
}

MotorCurveParams two_point_table() { return {511, {0.0, 1.0}, {0.0, 2.827}}; }

std::string table_error(const MotorCurveParams& params) {
  return invalid_argument_message([&] { MotorCurve{params}; });
}

TEST(MotorCurveValidation, AcceptsTheSmallestTable) {
  const MotorCurve curve(two_point_table());
  EXPECT_NEAR(curve.velocity_radps(0.5), 1.4135, 1e-12);
}

TEST(MotorCurveValidation, NamesTheFieldAndTheIndex) {
  MotorCurveParams params = Params{}.motor_curves.at(0);
  params.duty[4] = 0.3;
  EXPECT_THAT(table_error(params), HasSubstr("duty[4] = 0.3 must be greater than duty[3] = 0.3"));

  params = Params{}.motor_curves.at(0);
  params.no_load_speed_radps[5] = kNaN;
  EXPECT_THAT(table_error(params), HasSubstr("no_load_speed_radps[5] = nan must be finite"));

  params = Params{}.motor_curves.at(0);
  params.no_load_speed_radps[7] = 1.0;
  EXPECT_THAT(table_error(params), HasSubstr("no_load_speed_radps[7] = 1 must be greater"));
}

TEST(MotorCurveValidation, DutyRunsFromExactlyZeroToExactlyOne) {
  MotorCurveParams params = two_point_table();
  params.duty = {0.1, 1.0};
  EXPECT_THAT(table_error(params), HasSubstr("duty[0] = 0.1 must be exactly 0"));
  params.duty = {0.0, 0.9};
  EXPECT_THAT(table_error(params), HasSubstr("duty[1] = 0.9 must be exactly 1"));
  params = two_point_table();
  params.no_load_speed_radps = {0.05, 2.827};
  EXPECT_THAT(table_error(params), HasSubstr("no_load_speed_radps[0] = 0.05 must be exactly 0"));
}

TEST(MotorCurveValidation, RejectsMismatchedShortOrMislabelledTables) {
  MotorCurveParams params = two_point_table();
  params.no_load_speed_radps.push_back(3.0);
  EXPECT_THAT(table_error(params), HasSubstr("duty has 2 entries but no_load_speed_radps has 3"));
  params = {511, {0.0}, {0.0}};
  EXPECT_THAT(table_error(params), HasSubstr("at least 2"));
  params = two_point_table();
  params.icr = 100;
  EXPECT_THAT(table_error(params), HasSubstr("icr must lie in 255..2047"));
}

TEST(SelectMotorCurve, FindsTheTableForIcrOrListsTheAvailableOnes) {
  const Params params;
  EXPECT_EQ(&select_motor_curve(params.motor_curves, 511), &params.motor_curves.at(0));
  EXPECT_THAT(invalid_argument_message([&] { select_motor_curve(params.motor_curves, 1023); }),
              HasSubstr("no motor curve for icr 1023 (available: 511)"));
  EXPECT_THAT(invalid_argument_message([] { select_motor_curve({}, 511); }),
              HasSubstr("available: none"));
}

}  // namespace
}  // namespace marsokhod::adaptation
