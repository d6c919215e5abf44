#include "core/mobility/lever_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mobility_test_support.hpp"

namespace marsokhod::mobility {
namespace {

using testing::central_difference;
using testing::expect_invalid_argument;
using testing::kInfinity;
using testing::kNaN;

const GeometryParams kGeometry;  // a = 0.145 m, b = 0.413 m, r = 0.125 m

// Figure 3.3: γf = −p6, γr = +p7.
TEST(LeverGeometry, BendingFollowsTheJointSigns) {
  EXPECT_EQ(front_joint_bending_rad(-2.1), 2.1);
  EXPECT_EQ(rear_joint_bending_rad(1.85), 1.85);
  EXPECT_EQ(front_lever(-2.1, kGeometry).bending_rad, 2.1);
  EXPECT_EQ(rear_lever(1.85, kGeometry).bending_rad, 1.85);
}

// Contracted: acos(0.145/0.413) = acos(0.351090) = 1.212062 rad (Remark 3.1's 1.2121). There the
// angle at the exterior axle is right: c = sqrt(b² − a²) = sqrt(0.170569 − 0.021025) = 0.386709 m
// (chapter 6.2.2: "the wheel base ranges from 0.387") and α = asin(a/b) = 0.358735 rad (the
// chapter 3.1 table's α MAX 0.359).
TEST(LeverGeometry, ContractedLeverIsVertical) {
  const double gamma = contracted_bending_rad(kGeometry);
  EXPECT_NEAR(gamma, 1.212062, 1e-6);
  EXPECT_NEAR(axle_clearance_m(gamma, kGeometry), 0.386709, 1e-6);
  EXPECT_NEAR(axle_clearance_m(gamma, kGeometry), std::sqrt(0.413 * 0.413 - 0.145 * 0.145), 1e-15);
  EXPECT_NEAR(lever_inclination_rad(gamma, kGeometry), std::asin(0.145 / 0.413), 1e-12);
  EXPECT_NEAR(lever_inclination_rad(gamma, kGeometry), 0.358735, 1e-6);
}

// Extended (γ = 2.55, cos = −0.830054): c² = 0.191594 + 2·0.145·0.413·0.830054 = 0.291011,
// c = 0.539453 m. Chapter 6.2.2 prints 0.537 m for this end of (5.3); the law of cosines gives
// 0.5395 (0.537 would need γ = 2.513), so the thesis' number is 2.5 mm short.
TEST(LeverGeometry, ExtendedClearanceIsComputedNotTheThesisRounding) {
  EXPECT_NEAR(axle_clearance_m(2.55, kGeometry), 0.539453, 1e-6);
  EXPECT_GT(axle_clearance_m(2.55, kGeometry) - 0.537, 0.002);
}

// Example 5.4's γf = 2.1 (cos = −0.504846): c² = 0.191594 + 0.119770·0.504846 = 0.252055,
// c = 0.502055 m; α = acos((b² + c² − a²)/(2bc)) = acos(0.401603/0.414698) = 0.251964 rad.
TEST(LeverGeometry, HandValuesAtExample54) {
  EXPECT_NEAR(axle_clearance_m(2.1, kGeometry), 0.502055, 1e-6);
  EXPECT_NEAR(lever_inclination_rad(2.1, kGeometry), 0.251964, 1e-6);
  const Lever lever = front_lever(-2.1, kGeometry);
  EXPECT_NEAR(lever.clearance_m, 0.502055, 1e-6);
  EXPECT_NEAR(lever.inclination_rad, 0.251964, 1e-6);
}

// Lemma 5.3 against finite differences of c(γ) and α(γ), over the whole (5.3) range; the angle
// rates of the exterior and the joint vertex add up to 1 (γ − φ + φ = γ).
TEST(LeverGeometry, LemmaRatesAreTheDerivatives) {
  for (double gamma = 1.2121; gamma <= 2.55; gamma += 0.01) {
    const LeverRates rates = lever_rates(gamma, kGeometry);
    const double clearance_rate =
        central_difference([](double g) { return axle_clearance_m(g, kGeometry); }, gamma);
    const double inclination_rate =
        central_difference([](double g) { return lever_inclination_rad(g, kGeometry); }, gamma);
    ASSERT_NEAR(rates.clearance_m_per_rad, clearance_rate, 1e-9) << gamma;
    ASSERT_NEAR(rates.joint_angle_rate, -inclination_rate, 1e-9) << gamma;
    ASSERT_NEAR(rates.exterior_angle_rate + rates.joint_angle_rate, 1.0, 1e-12) << gamma;
    ASSERT_GT(rates.clearance_m_per_rad, 0.0) << "c grows with γ on (5.3)";
  }
}

// Figure 3.3: the center unit is tilted by ½(αf − αr); equal levers leave it level.
TEST(LeverGeometry, CenterUnitPitchIsHalfTheInclinationDifference) {
  EXPECT_NEAR(center_unit_pitch_rad(-2.1, 2.1, kGeometry), 0.0, 1e-15);
  EXPECT_NEAR(center_unit_pitch_rad(-1.212062, 2.1, kGeometry), 0.5 * (0.358735 - 0.251964), 1e-6);
}

// (5.3) from JointParams: p6 ∈ [−2.55, −1.2121], p7 ∈ [1.2121, 2.55].
TEST(LeverGeometry, JointBoundsComeFromTheParams) {
  const JointParams joints;
  const JointBounds front = front_joint_bounds(joints);
  const JointBounds rear = rear_joint_bounds(joints);
  EXPECT_EQ(front.min_rad, -2.55);
  EXPECT_EQ(front.max_rad, -1.2121);
  EXPECT_EQ(rear.min_rad, 1.2121);
  EXPECT_EQ(rear.max_rad, 2.55);
  EXPECT_TRUE(front.contains(-2.0));
  EXPECT_FALSE(front.contains(-1.2));
  EXPECT_EQ(front.clamp(-1.2), -1.2121);
  EXPECT_EQ(rear.clamp(3.0), 2.55);
  EXPECT_EQ(rear.clamp(2.0), 2.0);
}

TEST(LeverGeometry, RejectsNonFiniteInputsNamingThem) {
  expect_invalid_argument([] { front_joint_bending_rad(kNaN); }, {"p6"});
  expect_invalid_argument([] { rear_joint_bending_rad(kInfinity); }, {"p7"});
  expect_invalid_argument([] { axle_clearance_m(kNaN, kGeometry); }, {"bending_rad"});
  expect_invalid_argument([] { lever_rates(-kInfinity, kGeometry); }, {"bending_rad"});
  expect_invalid_argument([] { JointBounds{-2.55, -1.2121}.clamp(kNaN); }, {"position_rad"});
}

TEST(LeverGeometry, RejectsImpossibleParameters) {
  GeometryParams swapped;
  swapped.joint_to_exterior_axle_m = 0.5;
  expect_invalid_argument([&] { contracted_bending_rad(swapped); }, {"shorter", "acos(a/b)"});
  GeometryParams no_radius;
  no_radius.wheel_radius_m = 0.0;
  expect_invalid_argument([&] { validate(no_radius); }, {"wheel_radius_m"});
  JointParams empty;
  empty.front_min_rad = -1.0;
  expect_invalid_argument([&] { front_joint_bounds(empty); }, {"front joint bounds", "min < max"});
  JointParams nan_rear;
  nan_rear.rear_max_rad = kNaN;
  expect_invalid_argument([&] { rear_joint_bounds(nan_rear); }, {"rear joint bounds"});
  JointParams no_tolerance;
  no_tolerance.target_tolerance_rad = 0.0;
  expect_invalid_argument([&] { validate(no_tolerance); }, {"target_tolerance_rad"});
}

}  // namespace
}  // namespace marsokhod::mobility
