// The dead reckoning of pose_estimator.hpp against closed forms: a straight line, a full circle,
// a slope's projection, and the covariance's random walks.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/estimation/pose_estimator.hpp"

namespace marsokhod::estimation {
namespace {

constexpr double kH = 0.0156;  // 64 Hz
constexpr double kRadius = 0.125;

// Centre wheels at w rad/s, the gyro at ω, for n cycles: the encoders' angles go on from where
// the last call left them. An estimator's first call begins with one cycle standing, the angles'
// origin (the first update has no change to count).
struct Odometer : PoseEstimator {
  using PoseEstimator::PoseEstimator;
  double angle_rad = 0.0;
  bool begun = false;
};

const Pose& drive(Odometer& e, double w, double omega, int n, double slope = 0.0,
                  double load = 0.0) {
  OdometryInput in;
  in.period_s = kH;
  if (!e.begun) {
    e.begun = true;
    e.update(in);
  }
  in.yaw_rate_radps = omega;
  in.slope_rad = slope;
  in.left_no_load_radps = w;
  in.right_no_load_radps = w;
  in.left_load_radps = load;
  in.right_load_radps = load;
  double& angle = e.angle_rad;
  for (int k = 0; k < n; ++k) {
    angle += w * kH;
    in.left_angle_rad = angle;
    in.right_angle_rad = angle;
    e.update(in);
  }
  return e.pose();
}

TEST(PoseEstimator, AStraightRunCoversRTimesTheWheelAngle) {
  Odometer e(kRadius);
  const Pose& p = drive(e, 2.0, 0.0, 641);  // 10.0 s: 0.125 · 2 · 641 · 0.0156 = 2.5038 m
  EXPECT_NEAR(p.x_m, kRadius * 2.0 * 641 * kH, 1e-12);
  EXPECT_EQ(p.y_m, 0.0);
  EXPECT_EQ(p.heading_rad, 0.0);
  EXPECT_NEAR(p.speed_mps, 0.25, 1e-12);
  EXPECT_NEAR(p.distance_m, p.x_m, 1e-12);
  // Backward: the same distance back to the start.
  drive(e, -2.0, 0.0, 641);
  EXPECT_NEAR(e.pose().x_m, 0.0, 1e-12);
  EXPECT_NEAR(e.pose().distance_m, 2.0 * kRadius * 2.0 * 641 * kH, 1e-12);
}

TEST(PoseEstimator, AFullCircleClosesOnItselfWithTheHeadingTurnedOnce) {
  // v = 0.25 m/s, ω chosen so that 400 cycles make 2π: a regular 400-gon by the midpoint rule.
  Odometer e(kRadius);
  const double omega = 2.0 * std::numbers::pi / (400 * kH);
  const Pose& p = drive(e, 2.0, omega, 400);
  EXPECT_NEAR(p.heading_rad, 2.0 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(p.x_m, 0.0, 1e-12);
  EXPECT_NEAR(p.y_m, 0.0, 1e-12);
  // A quarter circle ends at (R, R) turning left (y positive): R = v/ω for the arc; the midpoint
  // rule's steps of length Δs along the mid-heading make it R·(Δψ/2)/sin(Δψ/2) (Σ of a geometric
  // series of e^(i(k+½)Δψ)), 1.0000016·R here.
  Odometer q(kRadius);
  drive(q, 2.0, omega, 100);
  const double dpsi = omega * kH;
  const double radius = 0.25 / omega * (dpsi / 2.0) / std::sin(dpsi / 2.0);
  EXPECT_NEAR(q.pose().x_m, radius, 1e-12);
  EXPECT_NEAR(q.pose().y_m, radius, 1e-12);
}

TEST(PoseEstimator, OnASlopeTheDistanceIsProjectedToTheHorizontal) {
  Odometer e(kRadius);
  const Pose& p = drive(e, 2.0, 0.0, 641, 0.3);  // 17°
  EXPECT_NEAR(p.x_m, kRadius * 2.0 * 641 * kH * std::cos(0.3), 1e-12);
}

TEST(PoseEstimator, TheCentreUnitsPitchTurnsItsWheelsOverTheGround) {
  // Wheel walking pitches the centre unit; the encoders count the wheels against it. With the
  // shafts still and the unit pitching 0.1 rad nose down, the wheels rolled r·0.1 = 12.5 mm
  // forward over the ground; pitching back brings the axle back (the Δθ add up to the change).
  Odometer e(kRadius);
  OdometryInput in;
  in.period_s = kH;
  e.update(in);  // the first pitch is where it starts: no change
  for (int k = 1; k <= 50; ++k) {
    in.pitch_rad = 0.1 * k / 50.0 + (k % 2 == 0 ? 0.003 : -0.003);  // with the sensor's noise
    e.update(in);
  }
  EXPECT_NEAR(e.pose().x_m, kRadius * (0.1 + 0.003), 1e-12);
  in.pitch_rad = 0.0;
  e.update(in);
  EXPECT_NEAR(e.pose().x_m, 0.0, 1e-12);
  // A rover already pitched when the pose starts (or resets) does not jump.
  PoseEstimator f(kRadius);
  in.pitch_rad = 0.2;
  f.update(in);
  EXPECT_EQ(f.pose().x_m, 0.0);
  f.reset();
  in.pitch_rad = -0.2;
  f.update(in);
  EXPECT_EQ(f.pose().x_m, 0.0);
}

TEST(PoseEstimator, TheCovarianceGrowsAsRandomWalksOfTheDistanceAndTheTime) {
  // No gyro noise: along a straight line only P_xx grows, k_s²·L.
  Odometer e(kRadius, {0.02, 0.0, 0.0});
  const Pose& p = drive(e, 2.0, 0.0, 641);
  EXPECT_NEAR(p.covariance[0], 0.02 * 0.02 * p.distance_m, 1e-12);
  EXPECT_NEAR(p.covariance[4], 0.0, 1e-15);
  EXPECT_NEAR(p.position_sigma_m(), 0.02 * std::sqrt(p.distance_m), 1e-12);
  // Wheels whose loads are as large as their commands (slipping): the distance counts twice.
  Odometer slipping(kRadius, {0.02, 0.0, 0.0});
  const Pose& s = drive(slipping, 2.0, 0.0, 641, 0.0, -2.0);
  EXPECT_NEAR(s.covariance[0], 2.0 * 0.02 * 0.02 * s.distance_m, 1e-12);
  // At rest the heading's variance grows with time, σ_ω²·t, whatever the period.
  Odometer still(kRadius, {0.02, 0.005, 0.02});
  drive(still, 0.0, 0.0, 641);  // and the first call's cycle standing
  EXPECT_NEAR(still.pose().heading_sigma_rad(), 0.005 * std::sqrt(642 * kH), 1e-12);
  EXPECT_EQ(still.pose().position_sigma_m(), 0.0);
  // A heading uncertain by σ_ψ spreads a straight run of L sideways by about L·σ_ψ.
  drive(still, 2.0, 0.0, 641);
  const double sideways = std::sqrt(still.pose().covariance[4]);
  EXPECT_GT(sideways, 2.5 * 0.005 * std::sqrt(641 * kH));
  EXPECT_LT(sideways, 2.6 * 0.005 * std::sqrt(2 * 641 * kH));
}

TEST(PoseEstimator, BadInputIsRejectedAndTheEstimateKept) {
  Odometer e(kRadius);
  drive(e, 2.0, 0.1, 10);
  const Pose before = e.pose();
  OdometryInput in;
  in.period_s = kH;
  in.yaw_rate_radps = std::nan("");
  EXPECT_THROW(e.update(in), std::invalid_argument);
  in.yaw_rate_radps = 0.0;
  in.period_s = 0.0;
  EXPECT_THROW(e.update(in), std::invalid_argument);
  EXPECT_EQ(e.pose().x_m, before.x_m);
  EXPECT_EQ(e.pose().covariance, before.covariance);
  EXPECT_THROW(PoseEstimator(0.0), std::invalid_argument);
  EXPECT_THROW(PoseEstimator(kRadius, {-0.1, 0.0, 0.0}), std::invalid_argument);
  e.reset();
  EXPECT_EQ(e.pose().x_m, 0.0);
  EXPECT_EQ(e.pose().distance_m, 0.0);
}

}  // namespace
}  // namespace marsokhod::estimation
