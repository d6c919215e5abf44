#include "core/adaptation/load_torque.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "adaptation_test_util.hpp"

namespace marsokhod::adaptation {
namespace {

using test::invalid_argument_message;
using test::kInf;
using test::kNaN;
using ::testing::HasSubstr;

constexpr double kTolerance = 1e-12;

// (4.7) with Procedure 4.13's peak torque 5.51 N m at d = 0.3:
//   τ d ≥ 0: l = 5.51 · 0.030 = 0.1653 rad/s      τ d < 0: l = −5.51 · 0.015 = −0.08265 rad/s
TEST(LoadFromTorque, Procedure4_13PeakTorque) {
  const LoadParams load;
  EXPECT_NEAR(load_from_torque(5.51, 0.3, load), 0.1653, kTolerance);
  EXPECT_NEAR(load_from_torque(-5.51, 0.3, load), -0.08265, kTolerance);
}

// Procedure 4.14's ±2.98 N m while driving backwards, d = −0.5:
//   τ = −2.98: τ d ≥ 0, l = −2.98 · 0.030 = −0.0894;   τ = 2.98: l = 2.98 · 0.015 = 0.0447
TEST(LoadFromTorque, DrivingBackwards) {
  const LoadParams load;
  EXPECT_NEAR(load_from_torque(-2.98, -0.5, load), -0.0894, kTolerance);
  EXPECT_NEAR(load_from_torque(2.98, -0.5, load), 0.0447, kTolerance);
}

// d = 0 makes τ d = 0 ≥ 0, so B⁺ applies in both directions; no torque, no load.
TEST(LoadFromTorque, StandingMotorUsesTheSameSignGain) {
  const LoadParams load;
  EXPECT_NEAR(load_from_torque(1.0, 0.0, load), 0.030, kTolerance);
  EXPECT_NEAR(load_from_torque(-1.0, 0.0, load), -0.030, kTolerance);
  EXPECT_EQ(load_from_torque(0.0, -0.7, load), 0.0);
}

TEST(TorqueFromLoad, InvertsTheHandWorkedValues) {
  const LoadParams load;
  EXPECT_NEAR(torque_from_load(0.1653, 0.3, load), 5.51, kTolerance);
  EXPECT_NEAR(torque_from_load(-0.08265, 0.3, load), -5.51, kTolerance);
  EXPECT_NEAR(torque_from_load(-0.0894, -0.5, load), -2.98, kTolerance);
  EXPECT_NEAR(torque_from_load(0.0447, -0.5, load), 2.98, kTolerance);
  EXPECT_EQ(torque_from_load(0.0, 0.5, load), 0.0);
}

TEST(LoadTorque, RoundTripsOverAGridWithTheSameSign) {
  const LoadParams load;
  for (int t = -100; t <= 100; ++t) {
    for (int d = -20; d <= 20; ++d) {
      const double torque_nm = t / 10.0;
      const double duty = d / 20.0;
      const double load_radps = load_from_torque(torque_nm, duty, load);
      ASSERT_EQ(std::signbit(load_radps), std::signbit(torque_nm)) << torque_nm << ", " << duty;
      ASSERT_NEAR(torque_from_load(load_radps, duty, load), torque_nm, kTolerance)
          << torque_nm << ", " << duty;
    }
  }
}

TEST(LoadTorque, RejectsInvalidInputsByName) {
  const LoadParams load;
  EXPECT_THAT(invalid_argument_message([&] { load_from_torque(kNaN, 0.3, load); }),
              HasSubstr("load_from_torque: torque_nm = nan"));
  EXPECT_THAT(invalid_argument_message([&] { torque_from_load(kInf, 0.3, load); }),
              HasSubstr("torque_from_load: load_radps = inf"));
  EXPECT_THAT(invalid_argument_message([&] { load_from_torque(1.0, 1.5, load); }),
              HasSubstr("duty = 1.5"));
  LoadParams broken;
  broken.gain_opposite_sign_radps_per_nm = 0.0;
  EXPECT_THAT(invalid_argument_message([&] { torque_from_load(1.0, 0.3, broken); }),
              HasSubstr("load.gain_opposite_sign_radps_per_nm = 0"));
  EXPECT_THAT(invalid_argument_message([&] {
                load_from_torque(1e308, 0.3, LoadParams{1e10, 1.0});
              }),
              HasSubstr("overflowed"));
}

}  // namespace
}  // namespace marsokhod::adaptation
