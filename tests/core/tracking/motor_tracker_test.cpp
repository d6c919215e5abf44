#include "core/tracking/motor_tracker.hpp"

#include <array>
#include <cstdlib>
#include <limits>
#include <numbers>

#include "tracking_test_support.hpp"

namespace marsokhod::tracking {
namespace {

using testing::EmulatedMotorController;
using testing::invalid_argument_message;

constexpr double kRadPerCount = 2.0 * std::numbers::pi / 115000.0;

TEST(MotorTracker, FirstResponseIsTheOrigin) {
  // Motor 6 (AF) starts at p̄⁰ = −1.2121 (Remark 3.1) at the given start time.
  MotorTracker tracker(MotorParams{}, kFrontJoint, 2.5);
  EXPECT_DOUBLE_EQ(tracker.sample().position_rad, -1.2121);
  EmulatedMotorController controller(kFrontJoint, 777, 60000);
  const MotorSample& sample = tracker.update(controller.respond(1727), 0);
  EXPECT_DOUBLE_EQ(sample.time_s, 2.5);
  EXPECT_DOUBLE_EQ(sample.position_rad, -1.2121);
  EXPECT_NEAR(sample.velocity_radps, 2.879549, 1e-6);  // 1727·25π/47104
}

TEST(MotorTracker, TimePositionAndVelocityOverManyCycles) {
  // 64 Hz at con = 0: 31250 ticks (15.625 ms) and 800 pulses per cycle, 200 cycles:
  // t = 200·0.015625 = 3.125 s; p̄ = 160000 pulses · 2π/115000 = 8.7418 rad; 800 pulses per
  // 15.625 ms is 51200 pulses/s; vel counts them per T(0) = 32.768 ms: 1677.7 → 1678, and
  // w̄ = 1678·25π/47104 = 2.7978 rad/s (= 51200·2π/115000 = 2.7974 up to rounding of vel).
  MotorTracker tracker(MotorParams{}, kCenterLeft);
  EmulatedMotorController controller(kCenterLeft, 65000, 65000);
  tracker.update(controller.respond(), 0);
  for (int k = 0; k < 200; ++k) {
    controller.turn(800);
    controller.advance_clock(31250);
    tracker.update(controller.respond(1678), 0);
  }
  EXPECT_NEAR(tracker.sample().time_s, 3.125, 1e-12);
  EXPECT_NEAR(tracker.sample().position_rad, 160000 * kRadPerCount, 1e-9);
  EXPECT_NEAR(tracker.sample().position_rad, 8.7418, 1e-4);
  EXPECT_NEAR(tracker.sample().velocity_radps, 2.7978, 1e-4);
}

TEST(MotorTracker, RejectsForeignNodeAndBadConWithoutChange) {
  MotorTracker tracker(MotorParams{}, kFrontLeft);
  EmulatedMotorController controller(kFrontLeft);
  tracker.update(controller.respond(), 0);
  controller.turn(100);
  controller.advance_clock(1000);
  protocol::ControlResponse foreign = controller.respond(5);
  foreign.node = kFrontRight;
  EXPECT_THAT(invalid_argument_message([&] { tracker.update(foreign, 0); }),
              ::testing::HasSubstr("node 1"));
  EXPECT_THROW(tracker.update(controller.respond(5), 300), std::invalid_argument);
  protocol::ControlResponse too_fast = controller.respond(0x8000);
  EXPECT_THROW(tracker.update(too_fast, 0), std::invalid_argument);
  EXPECT_DOUBLE_EQ(tracker.sample().time_s, 0.0);
  EXPECT_DOUBLE_EQ(tracker.sample().position_rad, 0.0);
  EXPECT_DOUBLE_EQ(tracker.sample().velocity_radps, 0.0);
  EXPECT_THAT(invalid_argument_message([] { MotorTracker(MotorParams{}, kSensorNode); }),
              ::testing::HasSubstr("motor index 8"));
}

TEST(MotorTracker, InvalidParametersNamed) {
  MotorParams params;
  params.initial_position_rad[kRearJoint] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(invalid_argument_message([&] { AllMotorsTracker tracker(params); }),
              ::testing::HasSubstr("motors.initial_position_rad[7]"));
  params = MotorParams{};
  params.encoder_pulses_per_rev = 0;
  EXPECT_THAT(invalid_argument_message([&] { MotorTracker(params, 0); }),
              ::testing::HasSubstr("motors.encoder_pulses_per_rev"));
}

// Eight controllers, motor i turning (i − 3)·100 pulses and its clock ticking 31250 + 1000·i
// ticks per cycle. After 50 cycles: p̄_i = p̄⁰_i + 50·(i − 3)·100·2π/115000 and
// t_i = 50·(31250 + 1000·i)·0.5 µs, e.g. t_0 = 0.78125 s, p̄_7 = 1.2121 + 20000·2π/115000.
// Each response reports vel = |(i − 3)·100| with the measured dir: w̄_i = (i − 3)·100·25π/47104.
TEST(AllMotorsTracker, EightMotorsEachOnItsOwnClock) {
  const MotorParams params;
  AllMotorsTracker tracker(params);
  std::array<EmulatedMotorController, kMotorCount> controllers;
  std::array<protocol::ControlResponse, kMotorCount> responses;
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    controllers[i] =
        EmulatedMotorController(static_cast<std::uint8_t>(i), static_cast<std::uint16_t>(9000 * i));
    responses[i] = controllers[i].respond();
  }
  tracker.update(responses, 0);
  for (int k = 0; k < 50; ++k) {
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      const int pulses = (static_cast<int>(i) - 3) * 100;
      controllers[i].turn(pulses);
      controllers[i].advance_clock(31250 + 1000 * static_cast<std::uint32_t>(i));
      responses[i] = controllers[i].respond(static_cast<std::uint16_t>(std::abs(pulses)));
    }
    tracker.update(responses, 0);
  }
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    const double pulses = (static_cast<double>(i) - 3.0) * 100.0;
    EXPECT_NEAR(tracker.sample().position_rad[i],
                params.initial_position_rad[i] + 50.0 * pulses * kRadPerCount, 1e-9)
        << kMotorNames[i];
    EXPECT_NEAR(tracker.sample().time_s[i],
                50.0 * (31250.0 + 1000.0 * static_cast<double>(i)) * 0.5e-6, 1e-12)
        << kMotorNames[i];
    EXPECT_NEAR(tracker.sample().velocity_radps[i], pulses * 25.0 * std::numbers::pi / 47104.0,
                1e-12)
        << kMotorNames[i];
  }
  EXPECT_NEAR(tracker.sample().time_s[0], 0.78125, 1e-12);
}

TEST(AllMotorsTracker, MissingResponseSkipsOnlyThatMotor) {
  AllMotorsTracker tracker(MotorParams{});
  EmulatedMotorController wheel(kBackRight);
  tracker.update_motor(wheel.respond(), 0);
  wheel.turn(-500);
  wheel.advance_clock(2000);
  tracker.update_motor(wheel.respond(), 0);
  EXPECT_NEAR(tracker.sample().position_rad[kBackRight], -500 * kRadPerCount, 1e-12);
  EXPECT_NEAR(tracker.sample().time_s[kBackRight], 0.001, 1e-12);
  EXPECT_FALSE(tracker.motor(kBackLeft).started());
  EXPECT_DOUBLE_EQ(tracker.sample().position_rad[kRearJoint], 1.2121);
}

TEST(AllMotorsTracker, MisplacedResponseLeavesEveryMotorUnchanged) {
  AllMotorsTracker tracker(MotorParams{});
  std::array<protocol::ControlResponse, kMotorCount> responses{};
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    responses[i].node = static_cast<std::uint8_t>(i);
  }
  std::swap(responses[3], responses[4]);
  EXPECT_THAT(invalid_argument_message([&] { tracker.update(responses, 0); }),
              ::testing::HasSubstr("responses[3] comes from node 4"));
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    EXPECT_FALSE(tracker.motor(i).started()) << kMotorNames[i];
  }
  responses[7].node = kSensorNode;
  EXPECT_THROW(tracker.update_motor(responses[7], 0), std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::tracking
