#include "core/tracking/motor_velocity.hpp"

#include <numbers>

#include "tracking_test_support.hpp"

namespace marsokhod::tracking {
namespace {

using testing::invalid_argument_message;

TEST(MotorVelocity, FactorIs25PiOver47104) {
  // 2π·2e6/(115000·65536) = 4e6π/7.53664e9 = π/1884.16 = 25π/47104 = 0.0016673704 rad/s per pulse.
  EXPECT_NEAR(velocity_radps_per_count(0, 115000), 25.0 * std::numbers::pi / 47104.0, 1e-18);
  EXPECT_NEAR(velocity_radps_per_count(1, 115000), 25.0 * std::numbers::pi / (2.0 * 47104.0),
              1e-18);
}

TEST(MotorVelocity, NoLoadSpeedReading) {
  // vel = 1727 at con = 0: 1727·25π/47104 = 2.87955 rad/s ≈ w = 2.827 (vel ≤ ⌈1727.27(con+1)⌉).
  EXPECT_NEAR(motor_velocity_radps(1727, false, 0, 115000), 2.879549, 1e-6);
  // The same speed at con = 1 counts twice the pulses in the doubled period T(1).
  EXPECT_NEAR(motor_velocity_radps(3454, false, 1, 115000), 2.879549, 1e-6);
  // dir = 1 turns clockwise: negative.
  EXPECT_NEAR(motor_velocity_radps(1727, true, 0, 115000), -2.879549, 1e-6);
  EXPECT_EQ(motor_velocity_radps(0, true, 0, 115000), 0.0);
}

TEST(MotorVelocity, RejectsOutOfRangeRegisters) {
  EXPECT_NO_THROW(motor_velocity_radps(kVelocityMaxCounts, false, 255, 115000));
  EXPECT_THAT(invalid_argument_message([] { motor_velocity_radps(0x8000, false, 0, 115000); }),
              ::testing::HasSubstr("vel = 32768"));
  EXPECT_THAT(invalid_argument_message([] { motor_velocity_radps(10, false, 256, 115000); }),
              ::testing::HasSubstr("con"));
  EXPECT_THAT(invalid_argument_message([] { motor_velocity_radps(10, false, 0, -1); }),
              ::testing::HasSubstr("motors.encoder_pulses_per_rev"));
}

}  // namespace
}  // namespace marsokhod::tracking
