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
    correction += c.update(t, kH, yaw, used, still);
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

TEST(NullDriftCorrection, NoDriftNoCorrection) {
  NullDriftCorrection c(kScale, 64);
  double correction = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const double t = k * kH;
    const bool still = (k / 300) % 2 == 0;
    correction += c.update(t, kH, still ? 505.0 : 495.0, 505.0, still);
  }
  EXPECT_NEAR(correction, 0.0, 1e-12);
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
