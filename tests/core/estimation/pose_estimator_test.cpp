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

// Centre wheels at w rad/s, the gyro at ω, for n cycles.
const Pose& drive(PoseEstimator& e, double w, double omega, int n, double slope = 0.0,
                  double load = 0.0) {
  OdometryInput in;
  in.period_s = kH;
  in.yaw_rate_radps = omega;
  in.slope_rad = slope;
  in.left_velocity_radps = w;
  in.right_velocity_radps = w;
  in.left_no_load_radps = w;
  in.right_no_load_radps = w;
  in.left_load_radps = load;
  in.right_load_radps = load;
  for (int k = 0; k < n; ++k) e.update(in);
  return e.pose();
}

TEST(PoseEstimator, AStraightRunCoversRTimesTheWheelAngle) {
  PoseEstimator e(kRadius);
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
  PoseEstimator e(kRadius);
  const double omega = 2.0 * std::numbers::pi / (400 * kH);
  const Pose& p = drive(e, 2.0, omega, 400);
  EXPECT_NEAR(p.heading_rad, 2.0 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(p.x_m, 0.0, 1e-12);
  EXPECT_NEAR(p.y_m, 0.0, 1e-12);
  // A quarter circle ends at (R, R) turning left (y positive): R = v/ω for the arc; the midpoint
  // rule's steps of length Δs along the mid-heading make it R·(Δψ/2)/sin(Δψ/2) (Σ of a geometric
  // series of e^(i(k+½)Δψ)), 1.0000016·R here.
  PoseEstimator q(kRadius);
  drive(q, 2.0, omega, 100);
  const double dpsi = omega * kH;
  const double radius = 0.25 / omega * (dpsi / 2.0) / std::sin(dpsi / 2.0);
  EXPECT_NEAR(q.pose().x_m, radius, 1e-12);
  EXPECT_NEAR(q.pose().y_m, radius, 1e-12);
}

TEST(PoseEstimator, OnASlopeTheDistanceIsProjectedToTheHorizontal) {
  PoseEstimator e(kRadius);
  const Pose& p = drive(e, 2.0, 0.0, 641, 0.3);  // 17°
  EXPECT_NEAR(p.x_m, kRadius * 2.0 * 641 * kH * std::cos(0.3), 1e-12);
}

TEST(PoseEstimator, TheCovarianceGrowsAsRandomWalksOfTheDistanceAndTheTime) {
  // No gyro noise: along a straight line only P_xx grows, k_s²·L.
  PoseEstimator e(kRadius, {0.02, 0.0, 0.0});
  const Pose& p = drive(e, 2.0, 0.0, 641);
  EXPECT_NEAR(p.covariance[0], 0.02 * 0.02 * p.distance_m, 1e-12);
  EXPECT_NEAR(p.covariance[4], 0.0, 1e-15);
  EXPECT_NEAR(p.position_sigma_m(), 0.02 * std::sqrt(p.distance_m), 1e-12);
  // Wheels whose loads are as large as their commands (slipping): the distance counts twice.
  PoseEstimator slipping(kRadius, {0.02, 0.0, 0.0});
  const Pose& s = drive(slipping, 2.0, 0.0, 641, 0.0, -2.0);
  EXPECT_NEAR(s.covariance[0], 2.0 * 0.02 * 0.02 * s.distance_m, 1e-12);
  // At rest the heading's variance grows with time, σ_ω²·t, whatever the period.
  PoseEstimator still(kRadius, {0.02, 0.005, 0.02});
  drive(still, 0.0, 0.0, 641);
  EXPECT_NEAR(still.pose().heading_sigma_rad(), 0.005 * std::sqrt(641 * kH), 1e-12);
  EXPECT_EQ(still.pose().position_sigma_m(), 0.0);
  // A heading uncertain by σ_ψ spreads a straight run of L sideways by about L·σ_ψ.
  drive(still, 2.0, 0.0, 641);
  const double sideways = std::sqrt(still.pose().covariance[4]);
  EXPECT_GT(sideways, 2.5 * 0.005 * std::sqrt(641 * kH));
  EXPECT_LT(sideways, 2.6 * 0.005 * std::sqrt(2 * 641 * kH));
}

TEST(PoseEstimator, BadInputIsRejectedAndTheEstimateKept) {
  PoseEstimator e(kRadius);
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
