#include "driver/duty_rules.hpp"

#include <gtest/gtest.h>

#include <random>

namespace marsokhod::driver {
namespace {

const SafetyParams kSafety;  // step 0.05, band 0.02

TEST(NextDuty, RampsByAtMostOneStep) {
  EXPECT_DOUBLE_EQ(next_duty(0.0, 0.3, kSafety), 0.05);
  EXPECT_DOUBLE_EQ(next_duty(0.05, 0.3, kSafety), 0.10);
  EXPECT_DOUBLE_EQ(next_duty(0.28, 0.3, kSafety), 0.3);
  EXPECT_DOUBLE_EQ(next_duty(0.3, 0.0, kSafety), 0.25);
}

TEST(NextDuty, ReversalPassesThroughTheBand) {
  // +0.12 → −0.5: 0.07, 0.02, then drv may toggle only to |d| ≤ 0.02: −0.02, then −0.07 …
  double d = 0.12;
  std::vector<double> seen;
  for (int k = 0; k < 6; ++k) seen.push_back(d = next_duty(d, -0.5, kSafety));
  ASSERT_EQ(seen.size(), 6u);
  EXPECT_NEAR(seen[0], 0.07, 1e-12);
  EXPECT_NEAR(seen[1], 0.02, 1e-12);
  EXPECT_NEAR(seen[2], -0.02, 1e-12);  // the toggle, at pwm ≈ 0
  EXPECT_NEAR(seen[3], -0.07, 1e-12);
}

TEST(NextDuty, NaNKeepsThePreviousDuty) {
  EXPECT_EQ(next_duty(0.2, std::nan(""), kSafety), 0.2);
}

TEST(NextDuty, PropertiesOverRandomTargets) {
  std::mt19937 rng(64);
  std::uniform_real_distribution<double> target(-1.5, 1.5);
  double d = 0.0;
  for (int k = 0; k < 100000; ++k) {
    const double next = next_duty(d, target(rng), kSafety);
    EXPECT_LE(std::abs(next - d), kSafety.max_duty_step + 1e-12);
    EXPECT_LE(std::abs(next), 1.0);
    if ((next < 0.0) != (d < 0.0)) {
      EXPECT_LE(std::abs(next), kSafety.direction_change_duty + 1e-12);
    }
    d = next;
  }
}

TEST(ControlRequest, EncodesDutyDirectionAndEim) {
  // d = −0.5 at icr 511: pwm = round(255.5) = 256, drv = 1, 256/511 < 0.6 → eim = 1.
  const auto r = control_request(3, -0.5, 511);
  EXPECT_EQ(r.node, 3);
  EXPECT_EQ(r.pwm, 256);
  EXPECT_TRUE(r.drv);
  EXPECT_TRUE(r.eim);
  // d = 0.7: pwm = round(357.7) = 358 ≥ 0.6·511 = 306.6 → eim = 0.
  const auto f = control_request(0, 0.7, 511);
  EXPECT_EQ(f.pwm, 358);
  EXPECT_FALSE(f.drv);
  EXPECT_FALSE(f.eim);
  // d = 0 is sent forward, and duties beyond ±1 are clamped.
  EXPECT_FALSE(control_request(1, -0.0, 511).drv);
  EXPECT_EQ(control_request(1, 1.7, 511).pwm, 511);
  EXPECT_NEAR(duty_of(control_request(2, -0.25, 511), 511), -128.0 / 511, 1e-15);
}

}  // namespace
}  // namespace marsokhod::driver
