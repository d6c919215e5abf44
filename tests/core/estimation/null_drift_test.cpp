#include "core/estimation/null_drift.hpp"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace marsokhod::estimation {
namespace {

constexpr double kScale = 0.0170;  // rad/s per count, (3.4)
constexpr double kH = 0.015625;    // 64 readings a second

// The null drifting at 0.01 LSB/s, the ADIS16100's worst (chapter 3.3).
double true_null(double t) { return 505.3 + 0.01 * t; }

// Stands for [t0, t1), moves for [t1, t2) turning at 0.2 rad/s with the null frozen at what it was
// when the rover set off (as (3.4) does), stands from t2 on for `after` seconds. Returns the heading
// the gyro got wrong while moving and the correction the update gave.
std::pair<double, double> leg(NullDriftCorrection& c, double t0, double t1, double t2, double after) {
  double error = 0.0, correction = 0.0;
  const double frozen = true_null(t1);
  for (double t = t0; t < t2 + after; t += kH) {
    const bool still = t < t1 || t >= t2;
    const double rate = still ? 0.0 : 0.2;
    const double yaw = true_null(t) - rate / kScale;  // the reading (no noise here)
    const double used = still ? true_null(t) : frozen;
    if (!still) error += kScale * (used - yaw) * kH - rate * kH;  // estimate − truth
    correction += c.update(t, kH, yaw, used, still).heading_rad;
  }
  return {error, correction};
}

TEST(NullDriftCorrection, TakesALinearDriftBackOutOfTheLeg) {
  NullDriftCorrection c(kScale, 64);
  // 15 s of motion: the estimate falls behind by ½·0.01·15²·0.0170 = 0.0191 rad.
  const auto [error, correction] = leg(c, 0.0, 2.0, 17.0, 2.0);
  EXPECT_NEAR(error, -0.5 * 0.01 * 15.0 * 15.0 * kScale, 2e-4);
  EXPECT_NEAR(correction, -error, 1e-9);
  EXPECT_NEAR(c.last_correction_rad(), -error, 1e-9);
  // The next leg is anchored on the standing between: corrected as well.
  const auto [error2, correction2] = leg(c, 19.0, 19.0, 29.0, 1.5);
  EXPECT_NEAR(correction2, -error2, 1e-9);
}

TEST(NullDriftCorrection, TakesThePositionsDriftOutWithTheHeadings) {
  // Stands 2 s, drives 15 s straight along x at 0.15 m/s (the truth: heading 0), stands 2 s. The
  // dead reckoning integrates the gyro with the null frozen at the start: its heading falls
  // behind quadratically and its track bends off the line. The correction puts the heading back
  // and moves the position to within the second order of the heading's error (≤ 0.02 rad here:
  // L·c²/2 ≈ 1e-4 m).
  NullDriftCorrection c(kScale, 64);
  double x = 0.0, y = 0.0, psi = 0.0;
  PoseCorrection total;
  const double frozen = true_null(2.0);
  for (double t = 0.0; t < 19.0; t += kH) {
    const bool still = t < 2.0 || t >= 17.0;
    const double yaw = true_null(t);  // the true rate is 0
    const double used = still ? true_null(t) : frozen;
    const PoseCorrection k = c.update(t, kH, yaw, used, still);
    total.heading_rad += k.heading_rad;
    total.x_m += k.x_m;
    total.y_m += k.y_m;
    psi += k.heading_rad;
    x += k.x_m;
    y += k.y_m;
    const double omega = kScale * (used - yaw);  // (3.4) with the frozen null
    const double ds = still ? 0.0 : 0.15 * kH;
    const double mid = psi + 0.5 * omega * kH;
    x += ds * std::cos(mid);
    y += ds * std::sin(mid);
    psi += omega * kH;
    c.add_motion(ds, mid);
  }
  // Uncorrected the track would end 2.25 m along and y = ∫ v·ψ(t) dt off the line, with
  // ψ(t) = −½·0.01·0.0170·t²: −0.15·0.01·0.0170·15³/6 = −0.0143 m; the correction adds that back.
  EXPECT_NEAR(total.y_m, 0.15 * 0.01 * kScale * 15.0 * 15.0 * 15.0 / 6.0, 5e-4);
  EXPECT_NEAR(psi, 0.0, 1e-9);
  EXPECT_NEAR(y, 0.0, 2e-4);
  EXPECT_NEAR(x, 2.25, 2e-3);
}

TEST(NullDriftCorrection, NeedsAnAnchorOnBothSides) {
  NullDriftCorrection c(kScale, 64);
  // Standing only 0.5 s (32 readings) before the leg: no anchor, nothing corrected.
  auto [error, correction] = leg(c, 0.0, 0.5, 10.0, 2.0);
  EXPECT_LT(error, -1e-3);
  EXPECT_EQ(correction, 0.0);
  // Standing 0.5 s after a leg corrects nothing yet (and does not end the leg).
  NullDriftCorrection d(kScale, 64);
  auto [error3, correction3] = leg(d, 0.0, 2.0, 12.0, 0.5);
  EXPECT_LT(error3, -1e-3);
  EXPECT_EQ(correction3, 0.0);
}

TEST(NullDriftCorrection, BeginLegForgetsWhatMovedBeforeTheOdometry) {
  // The start-up: it stands 2 s, moves a joint (the readings' null frozen and drifting) for 1 s,
  // stands 2 s, and the odometry starts in the middle of that standing; then a 15-s leg.
  NullDriftCorrection c(kScale, 64);
  const auto [startup_error, startup_correction] = leg(c, 0.0, 2.0, 3.0, 0.5);
  EXPECT_EQ(startup_correction, 0.0);  // the standing after it is not a second long yet
  c.begin_leg();
  // The standing goes on 1.5 s more (the anchor is the whole 2 s), then the leg: corrected in
  // full, and nothing of the start-up's motion goes into the heading.
  const auto [error, correction] = leg(c, 3.5, 5.0, 20.0, 2.0);
  EXPECT_LT(startup_error, -1e-5);
  EXPECT_NEAR(error, -0.5 * 0.01 * 15.0 * 15.0 * kScale, 2e-4);
  EXPECT_NEAR(correction, -error, 1e-9);
  // Without begin_leg the start-up's motion would have been corrected as part of the leg.
  NullDriftCorrection d(kScale, 64);
  leg(d, 0.0, 2.0, 3.0, 0.5);
  const auto [error_d, correction_d] = leg(d, 3.5, 5.0, 20.0, 2.0);
  EXPECT_GT(std::abs(correction_d + error_d), 1e-5);
}

TEST(NullDriftCorrection, NoDriftNoCorrection) {
  NullDriftCorrection c(kScale, 64);
  double correction = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const double t = k * kH;
    const bool still = (k / 300) % 2 == 0;
    correction += c.update(t, kH, still ? 505.0 : 495.0, 505.0, still).heading_rad;
  }
  EXPECT_NEAR(correction, 0.0, 1e-12);
}

TEST(NullDriftCorrection, CountsHowLongTheRoverHasStood) {
  NullDriftCorrection c(kScale, 64);
  EXPECT_EQ(c.standing_s(), 0.0);
  for (int k = 1; k <= 100; ++k) c.update(k * kH, kH, 505.0, 505.0, true);
  EXPECT_NEAR(c.standing_s(), 100 * kH, 1e-12);  // 100 readings of kH each
  c.update(101 * kH, kH, 495.0, 505.0, false);
  EXPECT_EQ(c.standing_s(), 0.0);
  c.update(102 * kH, kH, 505.0, 505.0, true);
  EXPECT_NEAR(c.standing_s(), kH, 1e-12);
}

TEST(NullDriftCorrection, RejectsBadArguments) {
  EXPECT_THROW(NullDriftCorrection(0.0, 64), std::invalid_argument);
  EXPECT_THROW(NullDriftCorrection(kScale, 0), std::invalid_argument);
  NullDriftCorrection c(kScale, 64);
  EXPECT_THROW(c.update(0.0, 0.0, 505.0, 505.0, true), std::invalid_argument);
  EXPECT_THROW(c.update(0.0, kH, std::nan(""), 505.0, true), std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::estimation
