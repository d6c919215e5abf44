#include "core/mobility/elementary_motion.hpp"

#include <gtest/gtest.h>

#include <cstddef>

#include "mobility_test_support.hpp"

namespace marsokhod::mobility {
namespace {

using testing::expect_invalid_argument;
using testing::kInfinity;
using testing::kNaN;

MotorVector scaled(const MotorVector& motion, double coefficient) {
  MotorVector result{};
  add_scaled(result, motion, coefficient);
  return result;
}

// Chapter 5: 0.27 m/s on r = 0.12 m is v1 = 0.27/0.12 = 2.25 rad/s on every wheel; joints still.
TEST(ElementaryMotion, DriveStraightAssignsV1ToEveryWheel) {
  const MotorVector w = scaled(drive_straight_motion(), 0.27 / 0.12);
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    EXPECT_DOUBLE_EQ(w[i], 2.25) << kMotorNames[i];
  }
  EXPECT_EQ(w[kFrontJoint], 0.0);
  EXPECT_EQ(w[kRearJoint], 0.0);
}

// Chapter 5.1's illustration: cf = 0.558 m, cr = 0.392 m; F(c) = 5.3c + 0.04 gives
// F(0.558) = 2.9574 + 0.04 = 2.9974 and F(0.392) = 2.0776 + 0.04 = 2.1176. Layout (3.1): row 1 is
// [BL CL FL] = [−F(cr) −1 −F(cf)], row 3 is [BR CR FR] = [F(cr) 1 F(cf)].
TEST(ElementaryMotion, SpinMatrixFollowsTheLayout) {
  const MotorVector m2 = spin_motion(0.558, 0.392, SpinParams{});
  EXPECT_NEAR(m2[kFrontLeft], -2.9974, 1e-12);
  EXPECT_NEAR(m2[kBackLeft], -2.1176, 1e-12);
  EXPECT_EQ(m2[kCenterLeft], -1.0);
  EXPECT_NEAR(m2[kFrontRight], 2.9974, 1e-12);
  EXPECT_NEAR(m2[kBackRight], 2.1176, 1e-12);
  EXPECT_EQ(m2[kCenterRight], 1.0);
  EXPECT_EQ(m2[kFrontJoint], 0.0);
  EXPECT_EQ(m2[kRearJoint], 0.0);
}

// Procedure 5.1's ratio F̂ = ¼(w0 − w1 + w4 − w5) / ½(w2 − w3) evaluated on m2 itself gives
// ¼(−2F(cf) − 2F(cr)) / ½(−2) = ½(F(cf) + F(cr)): F(c) when the axles are equidistant (0.532 m of
// Figure 5.3: 5.3·0.532 + 0.04 = 2.8596).
TEST(ElementaryMotion, SpinReproducesProcedure51sRatio) {
  const MotorVector w = spin_motion(0.532, 0.532, SpinParams{});
  const double ratio = 0.25 * (w[0] - w[1] + w[4] - w[5]) / (0.5 * (w[2] - w[3]));
  EXPECT_NEAR(ratio, 2.8596, 1e-12);
  EXPECT_NEAR(spin_ratio(0.532, SpinParams{}), 2.8596, 1e-12);
}

// A positive wheel velocity drives forward, so v2 > 0 runs the right side forward and the left
// side backward: counter-clockwise seen from above. The yaw rate of the center axle is
// r·(w3 − w2)/track > 0.
TEST(ElementaryMotion, PositiveSpinTurnsCounterClockwise) {
  const MotorVector w = scaled(spin_motion(0.45, 0.45, SpinParams{}), 1.0);
  const GeometryParams geometry;
  const double yaw_rate =
      geometry.wheel_radius_m * (w[kCenterRight] - w[kCenterLeft]) / geometry.track_width_m;
  EXPECT_GT(yaw_rate, 0.0);
  for (const MotorIndex left : {kFrontLeft, kCenterLeft, kBackLeft}) {
    EXPECT_LT(w[left], 0.0) << kMotorNames[left];
  }
}

// m3 = [1 0 −1; 0 0; −1 0 1]: BL = 1, CL = 0, FL = −1, BR = −1, CR = 0, FR = 1.
TEST(ElementaryMotion, SidewaysDriftMatrix) {
  const MotorVector expected{-1.0, 1.0, 0.0, 0.0, 1.0, -1.0, 0.0, 0.0};
  EXPECT_EQ(sideways_drift_motion(), expected);
}

// SPEC "Matrices lost in figures": m4 = 1 on FR, m6 = 1 on motor 6, m7 = 1 on motor 7.
TEST(ElementaryMotion, SingleMotorMatrices) {
  EXPECT_EQ(trench_motion(), (MotorVector{0, 1, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(front_joint_motion(), (MotorVector{0, 0, 0, 0, 0, 0, 1, 0}));
  EXPECT_EQ(rear_joint_motion(), (MotorVector{0, 0, 0, 0, 0, 0, 0, 1}));
}

// Σ_{j=1..4} m_j v_j with v = (2, −0.5, 0.25, 1), cf = cr = 0.5 (F = 2.69):
// FL = 2 + 0.5·2.69 − 0.25 = 3.095, FR = 2 − 1.345 + 0.25 + 1 = 1.905, CL = 2.5, CR = 1.5,
// BL = 2 + 1.345 + 0.25 = 3.595, BR = 2 − 1.345 − 0.25 = 0.405.
TEST(ElementaryMotion, DrivingMotionSumsTheFourDrivingMatrices) {
  const MotorVector w = driving_motion({2.0, -0.5, 0.25, 1.0}, 0.5, 0.5, SpinParams{});
  const MotorVector expected{3.095, 1.905, 2.5, 1.5, 3.595, 0.405, 0.0, 0.0};
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    EXPECT_NEAR(w[i], expected[i], 1e-12) << kMotorNames[i];
  }
}

TEST(ElementaryMotion, RejectsNonFiniteInputsNamingThem) {
  expect_invalid_argument([] { spin_ratio(kNaN, SpinParams{}); }, {"clearance_m"});
  expect_invalid_argument([] { spin_motion(0.4, kInfinity, SpinParams{}); }, {"clearance_m"});
  expect_invalid_argument(
      [] {
        driving_motion({1.0, kNaN, 0.0, 0.0}, 0.4, 0.4, SpinParams{});
      },
      {"spin_radps (v2)"});
  expect_invalid_argument(
      [] {
        driving_motion({kNaN, 0.0, 0.0, 0.0}, 0.4, 0.4, SpinParams{});
      },
      {"drive_radps (v1)"});
  expect_invalid_argument([] { spin_ratio(0.4, SpinParams{kNaN, 0.04}); }, {"slope_per_m"});
  expect_invalid_argument(
      [] {
        MotorVector w{};
        add_scaled(w, drive_straight_motion(), kInfinity);
      },
      {"coefficient"});
}

}  // namespace
}  // namespace marsokhod::mobility
