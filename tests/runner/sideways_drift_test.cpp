// runner::SidewaysDrift: the sideways displacement over the last second, per second — what
// sideways-drift-soft-sand checks of Field Experiment 5.2.
#include "runner/sideways_drift.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>

namespace marsokhod::runner {
namespace {

constexpr double kCycleS = 0.0156;  // the driver's cycle, at which the metrics sample

TEST(SidewaysDrift, NothingUntilAWholeSecondLiesBehind) {
  SidewaysDrift drift;
  EXPECT_FALSE(drift.add(0.0, 0.0, 0.0, 0.0));
  EXPECT_FALSE(drift.add(0.5, 0.0, 0.01, 0.0));
  EXPECT_FALSE(drift.add(0.999, 0.0, 0.02, 0.0));
  const std::optional<double> first = drift.add(1.0, 0.0, 0.02, 0.0);
  ASSERT_TRUE(first);
  EXPECT_DOUBLE_EQ(*first, 0.02);  // 2 cm to the left in 1 s
}

TEST(SidewaysDrift, ASteadySideSlipIsItsSpeedAndDrivingAheadIsNone) {
  // Heading 30°, moving 0.2 m/s ahead and 0.03 m/s to its left: the left axis is (−sin ψ, cos ψ).
  const double yaw = std::numbers::pi / 6.0;
  SidewaysDrift drift;
  std::optional<double> last;
  for (int k = 0; k <= 200; ++k) {
    const double t = k * kCycleS;
    const double x = t * (0.2 * std::cos(yaw) - 0.03 * std::sin(yaw));
    const double y = t * (0.2 * std::sin(yaw) + 0.03 * std::cos(yaw));
    last = drift.add(t, x, y, yaw);
  }
  ASSERT_TRUE(last);
  EXPECT_NEAR(*last, 0.03, 1e-12);
}

TEST(SidewaysDrift, ShakingInPlaceIsNotDrift) {
  // The chassis shaking sideways at 10 Hz with a speed amplitude of 5 cm/s (0.8 mm of travel): its
  // instantaneous sideways speed passes 2 cm/s, but over any second it moves at most 1.6 mm.
  const double omega = 2.0 * std::numbers::pi * 10.0;
  const double amplitude_m = 0.05 / omega;
  SidewaysDrift drift;
  double largest = 0.0;
  for (int k = 0; k <= 1000; ++k) {
    const double t = k * kCycleS;
    if (const auto d = drift.add(t, 0.0, amplitude_m * std::sin(omega * t), 0.0)) {
      largest = std::max(largest, *d);
    }
  }
  EXPECT_GT(largest, 0.0);
  EXPECT_LE(largest, 2.0 * amplitude_m + 1e-12);  // two amplitudes over at least a second
  EXPECT_LT(largest, 0.002);
}

TEST(SidewaysDrift, MeasuresAlongTheRoversOwnLeft) {
  // Moved 1 cm along +x in a second while facing −y (ψ = −90°, left is +x): 1 cm/s sideways.
  SidewaysDrift drift;
  drift.add(0.0, 0.0, 0.0, -std::numbers::pi / 2.0);
  const auto d = drift.add(1.0, 0.01, 0.0, -std::numbers::pi / 2.0);
  ASSERT_TRUE(d);
  EXPECT_NEAR(*d, 0.01, 1e-15);
}

TEST(SidewaysDrift, DrivingAheadWhileTurningIsNoDrift) {
  // 0.1 m/s ahead, turning at 0.36 rad/s (a spin's rate), sampled every cycle: an arc of radius
  // 0.278 m. Projected on the last heading the second's displacement would read v·ω·T/2 =
  // 1.8 cm/s sideways; step by step along the heading the rover had, the chord of each cycle's
  // arc leans by half its turn, which the mean heading takes out: under 1e-6 m/s.
  const double v = 0.1, omega = 0.36, radius = v / omega;
  SidewaysDrift drift;
  double largest = 0.0;
  for (int k = 0; k <= 300; ++k) {
    const double t = k * kCycleS, yaw = omega * t;
    const auto d = drift.add(t, radius * std::sin(yaw), radius * (1.0 - std::cos(yaw)), yaw);
    if (d) largest = std::max(largest, *d);
  }
  EXPECT_LT(largest, 1e-6);
  // And a true side-slip while turning still shows: 0.03 m/s toward the rover's left.
  SidewaysDrift slipping;
  std::optional<double> last;
  double x = 0.0, y = 0.0;
  for (int k = 0; k <= 300; ++k) {
    const double t = k * kCycleS, yaw = omega * t;
    if (k > 0) {
      const double mid = omega * (t - 0.5 * kCycleS);
      x += (v * std::cos(mid) - 0.03 * std::sin(mid)) * kCycleS;
      y += (v * std::sin(mid) + 0.03 * std::cos(mid)) * kCycleS;
    }
    last = slipping.add(t, x, y, yaw);
  }
  ASSERT_TRUE(last);
  EXPECT_NEAR(*last, 0.03, 1e-4);
}

}  // namespace
}  // namespace marsokhod::runner
