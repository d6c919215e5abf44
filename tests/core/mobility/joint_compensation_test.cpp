#include "core/mobility/joint_compensation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>

#include "core/mobility/elementary_motion.hpp"
#include "core/mobility/lever_geometry.hpp"
#include "mobility_test_support.hpp"

namespace marsokhod::mobility {
namespace {

using testing::central_difference;
using testing::expect_invalid_argument;
using testing::geometry_with_radius;
using testing::kNaN;

MotorVector plus(const MotorVector& x, const MotorVector& y) {
  MotorVector sum = x;
  add_scaled(sum, y, 1.0);
  return sum;
}

// Example 5.4, first part: r = 0.125, γf = 2.1 (p6 = −2.1), ρf = 0.4. By hand: cf = 0.502055,
// u = ab·sin γ/(r·cf) = 0.059885·0.863209/(0.125·0.502055) = 0.823707;
// rear column (1 − ρf)u = 0.494224, front column −ρf·u − b(b − a cos γ)/cf²
// = −0.329483 − 0.413·0.486203/0.252059 = −1.126127. The example prints 0.4942 and −1.1261.
// The middle row of m6 + n6 is [0 1] (AB = 0, AF = 1).
TEST(JointCompensation, Example54FrontExteriorColumns) {
  const MotorVector w =
      plus(front_joint_motion(), front_joint_compensation(-2.1, 0.4, geometry_with_radius(0.125)));
  EXPECT_NEAR(w[kBackLeft], 0.4942, 5e-5);
  EXPECT_NEAR(w[kBackRight], 0.4942, 5e-5);
  EXPECT_NEAR(w[kFrontLeft], -1.1261, 5e-5);
  EXPECT_NEAR(w[kFrontRight], -1.1261, 5e-5);
  EXPECT_EQ(w[kFrontJoint], 1.0);
  EXPECT_EQ(w[kRearJoint], 0.0);
}

// Example 5.4, second part: r = 0.115, γr = 1.85, ρr = 0. By hand: cr = 0.473921,
// u = 0.059885·0.961275/(0.115·0.473921) = 1.056238 → front column (1 − ρr)u = 1.0562; rear
// column −b(b − a cos γr)/cr² = −0.413·0.452961/0.224601 = −0.832910 → −0.8329 (the example).
TEST(JointCompensation, Example54RearExteriorColumns) {
  const MotorVector w =
      plus(rear_joint_motion(), rear_joint_compensation(1.85, 0.0, geometry_with_radius(0.115)));
  EXPECT_NEAR(w[kBackLeft], -0.8329, 5e-5);
  EXPECT_NEAR(w[kBackRight], -0.8329, 5e-5);
  EXPECT_NEAR(w[kFrontLeft], 1.0562, 5e-5);
  EXPECT_NEAR(w[kFrontRight], 1.0562, 5e-5);
  EXPECT_EQ(w[kRearJoint], 1.0);
  EXPECT_EQ(w[kFrontJoint], 0.0);
}

// docs/design.md "Example 5.4": the center column follows the formula, 0.5959 and 1.1398 (docs/design.md
// rounds the second to 1.1400), not the example's 0.5331 and 1.0801. By hand for n6:
// 0.494224 + ½·0.145·(0.145 + 0.413·0.504846)/0.252059 = 0.494224 + 0.101678 = 0.595902.
TEST(JointCompensation, Example54CenterColumnFollowsTheFormula) {
  const MotorVector n6 = front_joint_compensation(-2.1, 0.4, geometry_with_radius(0.125));
  const MotorVector n7 = rear_joint_compensation(1.85, 0.0, geometry_with_radius(0.115));
  EXPECT_NEAR(n6[kCenterLeft], 0.5959, 5e-5);
  EXPECT_NEAR(n6[kCenterRight], 0.5959, 5e-5);
  EXPECT_NEAR(n7[kCenterLeft], 1.1398, 5e-5);
  EXPECT_GT(std::abs(n6[kCenterLeft] - 0.5331), 0.06);
  EXPECT_GT(std::abs(n7[kCenterLeft] - 1.0801), 0.05);
}

// The center column minus the far exterior column is ½·a(a − b cos γ)/c²; it equals the rate of
// the center unit's pitch ½(αf − αr) per unit joint velocity: ∂/∂p6 for n6, ∂/∂p7 for n7
// (finite differences over (5.3), both wheel radii, several ρ).
TEST(JointCompensation, CenterColumnIsTheRateOfTheCenterUnitPitch) {
  for (const double radius : {0.115, 0.125}) {
    const GeometryParams geometry = geometry_with_radius(radius);
    for (double gamma = 1.22; gamma <= 2.55; gamma += 0.03) {
      for (const double rho : {0.0, 0.4, 1.0}) {
        const MotorVector n6 = front_joint_compensation(-gamma, rho, geometry);
        const MotorVector n7 = rear_joint_compensation(gamma, rho, geometry);
        const double front_pitch_rate = central_difference(
            [&](double p6) { return center_unit_pitch_rad(p6, 1.5, geometry); }, -gamma);
        const double rear_pitch_rate = central_difference(
            [&](double p7) { return center_unit_pitch_rad(-1.5, p7, geometry); }, gamma);
        ASSERT_NEAR(n6[kCenterLeft] - n6[kBackLeft], front_pitch_rate, 1e-9) << gamma;
        ASSERT_NEAR(n7[kCenterRight] - n7[kFrontRight], rear_pitch_rate, 1e-9) << gamma;
      }
    }
  }
}

// The 1/r placement: only u is a linear rate. With the angle term b(b − a cos γ)/c² taken out of
// the joint's own exterior column, the two exterior wheels roll apart at r·(far − own) = r·u =
// ∂c/∂γ [m/rad], the rate of the axle distance (finite difference of c), for any ρ.
TEST(JointCompensation, ExteriorWheelsRollApartAtTheAxleDistanceRate) {
  const GeometryParams geometry = geometry_with_radius(0.115);
  for (double gamma = 1.22; gamma <= 2.55; gamma += 0.05) {
    const LeverRates rates = lever_rates(gamma, geometry);
    const double clearance_rate =
        central_difference([&](double g) { return axle_clearance_m(g, geometry); }, gamma);
    for (const double rho : {0.0, 0.3, 1.0}) {
      const MotorVector n6 = front_joint_compensation(-gamma, rho, geometry);
      const double own_linear = n6[kFrontLeft] + rates.exterior_angle_rate;
      ASSERT_NEAR(0.115 * (n6[kBackLeft] - own_linear), clearance_rate, 1e-9);
      ASSERT_NEAR(0.115 * clearance_wheel_rate(gamma, geometry), clearance_rate, 1e-9);
    }
  }
}

// Chapter 5.3: "at γ = acos(a/b) and ρ = 1, the wheel motors turn faster than the joint by a
// factor of up to 2.261". There sin γ = c/b and a cos γ = a²/b, so u = a/r and the own exterior
// column is −u − (b² − a²)/c² = −(1 + a/r): −(1 + 0.145/0.115) = −2.2609 on sand, −2.16 with
// r = 0.125. The far and center columns vanish (ρ = 1, a − b cos γ = 0).
TEST(JointCompensation, ContractedJointNeedsTheThesisFactor2261) {
  const double contracted = contracted_bending_rad(GeometryParams{});
  const MotorVector n6 = front_joint_compensation(-contracted, 1.0, geometry_with_radius(0.115));
  const MotorVector n7 = rear_joint_compensation(contracted, 1.0, geometry_with_radius(0.115));
  EXPECT_NEAR(n6[kFrontLeft], -2.261, 5e-4);
  EXPECT_NEAR(n6[kFrontLeft], -(1.0 + 0.145 / 0.115), 1e-12);
  EXPECT_NEAR(n7[kBackRight], -2.261, 5e-4);
  EXPECT_NEAR(n6[kBackLeft], 0.0, 1e-15);
  EXPECT_NEAR(n6[kCenterLeft], 0.0, 1e-15);
  EXPECT_NEAR(front_joint_compensation(-contracted, 1.0, geometry_with_radius(0.125))[kFrontLeft],
              -2.16, 1e-12);
}

// ρ = 0 keeps the joint's own exterior axle still: its wheel only cancels the lever's turn (no u
// term); ρ = 1 keeps the other two: the far column is 0.
TEST(JointCompensation, RhoChoosesWhichAxlesStay) {
  const GeometryParams geometry;
  const LeverRates rates = lever_rates(2.0, geometry);
  const MotorVector own_still = front_joint_compensation(-2.0, 0.0, geometry);
  EXPECT_NEAR(own_still[kFrontLeft], -rates.exterior_angle_rate, 1e-15);
  const MotorVector others_still = rear_joint_compensation(2.0, 1.0, geometry);
  EXPECT_EQ(others_still[kFrontLeft], 0.0);
  EXPECT_NEAR(others_still[kCenterLeft], 0.5 * rates.joint_angle_rate, 1e-15);
}

// walking_motion = m6 v6 + n6 w6 + m7 v7 + n7 w7, term by term.
TEST(JointCompensation, WalkingMotionSumsTheFourTerms) {
  const GeometryParams geometry;
  const WalkingInput input{-2.0, 1.7, 0.3, -0.4, 0.25, -0.35, 0.2, 0.9};
  const MotorVector n6 = front_joint_compensation(-2.0, 0.2, geometry);
  const MotorVector n7 = rear_joint_compensation(1.7, 0.9, geometry);
  const MotorVector w = walking_motion(input, geometry);
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    ASSERT_NEAR(w[i], 0.25 * n6[i] - 0.35 * n7[i], 1e-15) << kMotorNames[i];
  }
  EXPECT_EQ(w[kFrontJoint], 0.3);
  EXPECT_EQ(w[kRearJoint], -0.4);
}

TEST(JointCompensation, RejectsNonFiniteInputsNamingThem) {
  const GeometryParams geometry;
  expect_invalid_argument([&] { front_joint_compensation(kNaN, 0.5, geometry); }, {"p6"});
  expect_invalid_argument([&] { rear_joint_compensation(2.0, kNaN, geometry); }, {"ρr"});
  WalkingInput input{-2.0, 1.7, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  input.rear_joint_velocity_radps = kNaN;
  expect_invalid_argument([&] { walking_motion(input, geometry); }, {"w7"});
  input.rear_joint_velocity_radps = 0.0;
  input.front_axle_factor = kNaN;
  expect_invalid_argument([&] { walking_motion(input, geometry); }, {"ρf"});
}

}  // namespace
}  // namespace marsokhod::mobility
