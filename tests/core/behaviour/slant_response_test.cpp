#include "core/behaviour/slant_response.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "behaviour_test_support.hpp"
#include "core/behaviour/slope_estimate.hpp"

namespace marsokhod::behaviour {
namespace {

using test::invalid_argument_message;
using test::kNaN;
using ::testing::HasSubstr;

constexpr double kTolerance = 1e-12;
constexpr double kA = 0.145;  // a, joint to exterior axle
constexpr double kB = 0.413;  // b, center axle to joint
constexpr double kDegree = std::numbers::pi / 180.0;

// γ(15°) by hand: cos²15° = 0.933013, sin 15° = 0.258819, a cos²σ = 0.135287,
// R = sqrt(b² − a² cos²σ) = sqrt(0.170569 − 0.019617) = 0.388526, sin σ · R = 0.100558,
// cos γ = (0.135287 − 0.100558)/0.413 = 0.084089, γ = acos(0.084089) = 1.486607 rad (85.18°).
constexpr double kAngleAt15DegreesRad = 1.4866075;
// acos(a/b) = acos(0.351090) = 1.2120618 rad, the contracted pose.
constexpr double kContractedRad = 1.2120618;

double axle_distance_m(double joint_angle_rad) {
  return std::sqrt(kA * kA + kB * kB - 2.0 * kA * kB * std::cos(joint_angle_rad));
}

TEST(SlantResponse, JointAngleByHand) {
  const GeometryParams geometry;
  EXPECT_NEAR(gravity_parallel_joint_angle_rad(0.0, geometry), kContractedRad, 1e-7);
  EXPECT_NEAR(gravity_parallel_joint_angle_rad(15.0 * kDegree, geometry), kAngleAt15DegreesRad,
              1e-7);
  // σ = 90°: s = 0, cos γ = −(1/b) sqrt(b²) = −1, γ = π (the lever folded flat).
  EXPECT_NEAR(gravity_parallel_joint_angle_rad(90.0 * kDegree, geometry), std::numbers::pi, 1e-7);
}

// The derivation in the header: the printed γ(σ) solves a − b cos γ = −c sin σ literally for
// σ ≤ 0, and a − b cos γ = c |sin σ| (the downhill lever vertical) for every σ; it is even.
TEST(SlantResponse, PrintedFormulaSatisfiesTheDefiningRelationForTheDownhillJoint) {
  const GeometryParams geometry;
  for (double degrees = -80.0; degrees <= 80.0; degrees += 2.5) {
    const double slope_rad = degrees * kDegree;
    const double angle_rad = gravity_parallel_joint_angle_rad(slope_rad, geometry);
    const double lhs_m = kA - kB * std::cos(angle_rad);
    EXPECT_NEAR(lhs_m, axle_distance_m(angle_rad) * std::abs(std::sin(slope_rad)), kTolerance)
        << degrees;
    if (slope_rad <= 0.0) {
      EXPECT_NEAR(lhs_m, -axle_distance_m(angle_rad) * std::sin(slope_rad), kTolerance);
    }
    EXPECT_NEAR(angle_rad, gravity_parallel_joint_angle_rad(-slope_rad, geometry), kTolerance);
    EXPECT_GE(angle_rad, kContractedRad - 1e-7);
  }
}

// The other root of the squared relation, cos γ = (a cos²σ + |sin σ| R)/b, is what solves the
// printed relation literally for σ > 0: at 15° cos γ = (0.135287 + 0.100558)/0.413 = 0.571053,
// γ = 0.963009 rad, a contracted angle below acos(a/b) that (5.3) clips away; the slant
// response needs the extended root, which the printed formula gives.
TEST(SlantResponse, TheLiteralRootForAnAscentIsContracted) {
  const double slope_rad = 15.0 * kDegree;
  const double cos2 = std::cos(slope_rad) * std::cos(slope_rad);
  const double other_root_rad =
      std::acos((kA * cos2 + std::sin(slope_rad) * std::sqrt(kB * kB - kA * kA * cos2)) / kB);
  EXPECT_NEAR(other_root_rad, 0.963009, 1e-6);
  EXPECT_NEAR(kA - kB * std::cos(other_root_rad),
              -axle_distance_m(other_root_rad) * std::sin(slope_rad), kTolerance);
  EXPECT_LT(other_root_rad, JointParams{}.rear_min_rad);
}

TEST(SlantResponse, JointAngleGrowsWithTheSlope) {
  const GeometryParams geometry;
  double previous_rad = gravity_parallel_joint_angle_rad(0.0, geometry);
  for (double degrees = 1.0; degrees <= 90.0; degrees += 1.0) {
    const double angle_rad = gravity_parallel_joint_angle_rad(degrees * kDegree, geometry);
    EXPECT_GT(angle_rad, previous_rad) << degrees;
    previous_rad = angle_rad;
  }
}

// Feed the resting reading of a 15° pitch until g settles (0.99^4000 ≈ 3.4e-18), then take σ
// with equal lever inclinations (both contracted: α = acos(c/b) = acos(0.386709/0.413) =
// 0.358735), which cancel: σ = ±15° = ±0.261799 rad.
double settled_slope_rad(double pitch_rad) {
  const Vector3 reading_mps2{-9.81 * std::sin(pitch_rad), 0.0, -9.81 * std::cos(pitch_rad)};
  GravityEstimate estimate(9.81);
  for (int k = 0; k < 4000; ++k) {
    estimate.update(reading_mps2, FilterParams{}.gravity_lambda);
  }
  return terrain_slope_rad(estimate.direction(), 0.358735, 0.358735);
}

// Nose up 15°: the rear joint faces downhill; p7_min rises from 1.2121 to γ(15°) = 1.486607
// (by 0.274507 rad), the other bounds stay (5.3).
TEST(SlantResponse, NoseUpExtendsTheRearJoint) {
  const double slope_rad = settled_slope_rad(15.0 * kDegree);
  EXPECT_NEAR(slope_rad, 15.0 * kDegree, 1e-9);
  const JointBounds bounds =
      slant_joint_bounds(slope_rad, JointParams{}, GeometryParams{}, BehaviourSwitches{});
  EXPECT_NEAR(bounds.rear_min_rad, kAngleAt15DegreesRad, 1e-7);
  EXPECT_NEAR(bounds.rear_min_rad - 1.2121, 0.274507, 1e-6);
  EXPECT_EQ(bounds.rear_max_rad, 2.55);
  EXPECT_EQ(bounds.front_min_rad, -2.55);
  EXPECT_EQ(bounds.front_max_rad, -1.2121);
}

// Nose down 15°: the front joint faces downhill; p6_max falls from −1.2121 to −γ(15°).
TEST(SlantResponse, NoseDownExtendsTheFrontJoint) {
  const double slope_rad = settled_slope_rad(-15.0 * kDegree);
  EXPECT_NEAR(slope_rad, -15.0 * kDegree, 1e-9);
  const JointBounds bounds =
      slant_joint_bounds(slope_rad, JointParams{}, GeometryParams{}, BehaviourSwitches{});
  EXPECT_NEAR(bounds.front_max_rad, -kAngleAt15DegreesRad, 1e-7);
  EXPECT_EQ(bounds.front_min_rad, -2.55);
  EXPECT_EQ(bounds.rear_min_rad, 1.2121);
  EXPECT_EQ(bounds.rear_max_rad, 2.55);
}

// Flat: σ = 0 and γ(0) = 1.2120618 lies inside (5.3)'s 1.2121 (acos(a/b) rounded up), so no
// bound moves at all.
TEST(SlantResponse, FlatGroundMovesNothing) {
  const double slope_rad = settled_slope_rad(0.0);
  EXPECT_EQ(slope_rad, 0.0);
  const JointBounds bounds =
      slant_joint_bounds(slope_rad, JointParams{}, GeometryParams{}, BehaviourSwitches{});
  EXPECT_EQ(bounds.front_min_rad, -2.55);
  EXPECT_EQ(bounds.front_max_rad, -1.2121);
  EXPECT_EQ(bounds.rear_min_rad, 1.2121);
  EXPECT_EQ(bounds.rear_max_rad, 2.55);
}

// γ(70°) = 2.672157 > 2.55: the raised minimum stops at the maximum of (5.3), min = max.
// A narrower configured interval clips in the same way.
TEST(SlantResponse, BoundsStayInsideTheLimitsOf5_3) {
  const JointBounds steep =
      slant_joint_bounds(70.0 * kDegree, JointParams{}, GeometryParams{}, BehaviourSwitches{});
  EXPECT_EQ(steep.rear_min_rad, 2.55);
  EXPECT_EQ(steep.rear_max_rad, 2.55);
  const JointBounds steep_down =
      slant_joint_bounds(-70.0 * kDegree, JointParams{}, GeometryParams{}, BehaviourSwitches{});
  EXPECT_EQ(steep_down.front_max_rad, -2.55);
  EXPECT_EQ(steep_down.front_min_rad, -2.55);
  JointParams narrow;
  narrow.rear_max_rad = 1.4;
  const JointBounds clipped =
      slant_joint_bounds(15.0 * kDegree, narrow, GeometryParams{}, BehaviourSwitches{});
  EXPECT_EQ(clipped.rear_min_rad, 1.4);
  for (double degrees = -89.0; degrees <= 89.0; degrees += 1.0) {
    const JointBounds bounds =
        slant_joint_bounds(degrees * kDegree, JointParams{}, GeometryParams{}, BehaviourSwitches{});
    EXPECT_LE(bounds.front_min_rad, bounds.front_max_rad);
    EXPECT_LE(bounds.rear_min_rad, bounds.rear_max_rad);
    EXPECT_GE(bounds.front_min_rad, -2.55);
    EXPECT_LE(bounds.front_max_rad, -1.2121);
    EXPECT_GE(bounds.rear_min_rad, 1.2121);
    EXPECT_LE(bounds.rear_max_rad, 2.55);
  }
}

TEST(SlantResponse, SwitchedOffGivesTheBoundsOf5_3) {
  const JointBounds bounds =
      slant_joint_bounds(15.0 * kDegree, JointParams{}, GeometryParams{}, all_switched_off());
  EXPECT_EQ(bounds.rear_min_rad, 1.2121);
  EXPECT_EQ(bounds.front_max_rad, -1.2121);
}

TEST(SlantResponse, RejectsInvalidInputsByName) {
  EXPECT_THAT(invalid_argument_message([] {
                slant_joint_bounds(kNaN, JointParams{}, GeometryParams{}, BehaviourSwitches{});
              }),
              HasSubstr("gravity_parallel_joint_angle_rad: slope_rad = nan"));
  JointParams crossed;
  crossed.front_min_rad = -1.0;
  EXPECT_THAT(invalid_argument_message(
                  [&] { slant_joint_bounds(0.1, crossed, GeometryParams{}, BehaviourSwitches{}); }),
              HasSubstr("joints.front_min_rad exceeds joints.front_max_rad"));
  GeometryParams swapped;
  swapped.joint_to_exterior_axle_m = 0.5;
  EXPECT_THAT(invalid_argument_message([&] { gravity_parallel_joint_angle_rad(0.1, swapped); }),
              HasSubstr("must be shorter than"));
  JointParams infinite;
  infinite.rear_max_rad = std::numeric_limits<double>::infinity();
  EXPECT_THAT(invalid_argument_message([&] { joint_bounds_of(infinite); }),
              HasSubstr("joints.rear_max_rad = inf"));
}

}  // namespace
}  // namespace marsokhod::behaviour
