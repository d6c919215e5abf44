// The odometry frame seen from outside (odometry_frame.hpp): transforms worked out by hand, the
// round trip, and a tracker that unwraps the outer yaw and starts a new frame when told.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/estimation/odometry_frame.hpp"

namespace marsokhod::estimation {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(OdometryFrame, AFrameTurnedALeftQuarterSeesTheOuterXAxisToItsRight) {
  // Origin at (1, 2) facing +Y (outer). The outer point (1, 5) is 3 m ahead: local (3, 0);
  // (4, 2) is 3 m to the right: local (0, −3).
  const PlanarPose origin{1.0, 2.0, kPi / 2};
  const PlanarPose ahead = to_frame(origin, {1.0, 5.0, kPi / 2});
  EXPECT_NEAR(ahead.x_m, 3.0, 1e-12);
  EXPECT_NEAR(ahead.y_m, 0.0, 1e-12);
  EXPECT_NEAR(ahead.heading_rad, 0.0, 1e-12);
  const PlanarPose right = to_frame(origin, {4.0, 2.0, 0.0});
  EXPECT_NEAR(right.x_m, 0.0, 1e-12);
  EXPECT_NEAR(right.y_m, -3.0, 1e-12);
  EXPECT_NEAR(right.heading_rad, -kPi / 2, 1e-12);
}

TEST(OdometryFrame, FromFrameUndoesToFrame) {
  const PlanarPose origin{-3.5, 0.25, 2.7};
  for (const PlanarPose p : {PlanarPose{0.0, 0.0, 0.0}, PlanarPose{1.2, -4.0, 7.5},
                             PlanarPose{-10.0, 3.0, -9.0}}) {
    const PlanarPose local = to_frame(origin, p);
    const PlanarPose back = from_frame(origin, local);
    EXPECT_NEAR(back.x_m, p.x_m, 1e-12);
    EXPECT_NEAR(back.y_m, p.y_m, 1e-12);
    EXPECT_NEAR(back.heading_rad, p.heading_rad, 1e-12);
    // Distances do not change.
    EXPECT_NEAR(std::hypot(local.x_m, local.y_m),
                std::hypot(p.x_m - origin.x_m, p.y_m - origin.y_m), 1e-12);
  }
  // The origin is the frame's zero.
  const PlanarPose zero = to_frame(origin, origin);
  EXPECT_NEAR(zero.x_m, 0.0, 1e-12);
  EXPECT_NEAR(zero.y_m, 0.0, 1e-12);
  EXPECT_EQ(zero.heading_rad, 0.0);
}

TEST(OdometryFrameTracker, TheFirstObservationIsTheOrigin) {
  OdometryFrameTracker t;
  EXPECT_FALSE(t.started());
  t.observe(5.0, -1.0, 1.0, false);
  EXPECT_TRUE(t.started());
  EXPECT_EQ(t.pose().x_m, 0.0);
  EXPECT_EQ(t.pose().y_m, 0.0);
  EXPECT_EQ(t.pose().heading_rad, 0.0);
  // 2 m along the origin's heading (yaw 1 rad) and turned by 0.5 rad.
  t.observe(5.0 + 2.0 * std::cos(1.0), -1.0 + 2.0 * std::sin(1.0), 1.5, false);
  EXPECT_NEAR(t.pose().x_m, 2.0, 1e-12);
  EXPECT_NEAR(t.pose().y_m, 0.0, 1e-12);
  EXPECT_NEAR(t.pose().heading_rad, 0.5, 1e-12);
}

TEST(OdometryFrameTracker, TheYawIsUnwrappedAcrossPlusMinusPi) {
  OdometryFrameTracker t;
  t.observe(0.0, 0.0, 0.0, true);
  // A turn counter-clockwise by 1.5 turns in steps of 0.3 rad, fed wrapped into (−π, π].
  double yaw = 0.0;
  for (int k = 0; k < 31; ++k) {
    yaw += 0.3;
    t.observe(0.0, 0.0, std::remainder(yaw, 2.0 * kPi), false);
  }
  EXPECT_NEAR(t.pose().heading_rad, 9.3, 1e-9);
}

TEST(OdometryFrameTracker, ANewFrameStartsAtZeroAndKeepsTheUnwrappedYaw) {
  OdometryFrameTracker t;
  t.observe(0.0, 0.0, 3.0, true);
  t.observe(1.0, 0.0, -3.0, false);  // turned by 2π − 6 = +0.283 rad across π
  EXPECT_NEAR(t.pose().heading_rad, 2.0 * kPi - 6.0, 1e-12);
  t.observe(1.0, 0.0, -3.0, true);  // the driver restarts here
  EXPECT_EQ(t.pose().x_m, 0.0);
  EXPECT_EQ(t.pose().heading_rad, 0.0);
  EXPECT_NEAR(t.origin().heading_rad, 2.0 * kPi - 3.0, 1e-12);
  // 1 m further along the outer yaw −3 (= 2π − 3): straight ahead in the new frame.
  t.observe(1.0 + std::cos(-3.0), std::sin(-3.0), -3.0, false);
  EXPECT_NEAR(t.pose().x_m, 1.0, 1e-12);
  EXPECT_NEAR(t.pose().y_m, 0.0, 1e-12);
  EXPECT_NEAR(t.pose().heading_rad, 0.0, 1e-12);
}

}  // namespace
}  // namespace marsokhod::estimation
