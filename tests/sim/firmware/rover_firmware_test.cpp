#include "sim/firmware/rover_firmware.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <variant>

#include "core/protocol/codec.hpp"

namespace marsokhod::sim {
namespace {

using protocol::CanFrame;

constexpr SimTimeNs kMs = 1'000'000;
constexpr double kRadPerPulse = 2.0 * std::numbers::pi / 115000.0;

Params wheels_only_params() {
  Params params;
  params.motors.initial_position_rad = {};  // all shafts at 0 for hand-worked counts
  return params;
}

void send_cycle(RoverFirmware& firmware, SimTimeNs time_ns, std::uint16_t pwm) {
  for (std::uint8_t node = 0; node < 8; ++node) {
    firmware.send(protocol::encode(protocol::ControlRequest{node, false, true, pwm}), time_ns);
  }
  firmware.send(protocol::encode(protocol::MeasurementRequest{}), time_ns);
}

std::vector<BusDelivery> run(RoverFirmware& firmware, SimTimeNs from_ns, SimTimeNs to_ns,
                             const MotorVector& angles = {}) {
  std::vector<BusDelivery> received;
  for (SimTimeNs time_ns = from_ns + kMs; time_ns <= to_ns; time_ns += kMs) {
    for (const BusDelivery& delivery : firmware.advance_to(time_ns, angles, SensorTruthSample{})) {
      received.push_back(delivery);
    }
  }
  return received;
}

TEST(RoverFirmware, OneCycleIsAnsweredByAllNineControllers) {
  RoverFirmware firmware(wheels_only_params(), exact_sim_truth(Params{}), 1);
  send_cycle(firmware, 0, 200);
  const std::vector<BusDelivery> received = run(firmware, 0, 5 * kMs);
  ASSERT_EQ(received.size(), 9U);
  for (const BusDelivery& delivery : received) {
    const protocol::DecodeResult decoded = protocol::decode(delivery.frame);
    ASSERT_TRUE(decoded.ok()) << decoded.error().reason;
    EXPECT_EQ(protocol::type_of(decoded.message()), 1);  // 0xi1 and 0x81
    EXPECT_EQ(static_cast<int>(protocol::node_of(decoded.message())), delivery.origin);
  }
  // µ0's request (02 00 C8: 76 bits, delivered after 73 µs) is answered 50 µs later; by then
  // µ1's request holds the bus, so µ0's answer (lower ID than µ2's request) is next.
  const CanFrame request = protocol::encode(protocol::ControlRequest{0, false, true, 200});
  EXPECT_EQ(frame_timing(request).total_bits, 76);
  EXPECT_EQ(received.front().origin, 0);
  EXPECT_EQ(received.front().ready_ns, 73'000 + 50'000);
  const CanFrame second = protocol::encode(protocol::ControlRequest{1, false, true, 200});
  EXPECT_EQ(received.front().start_ns,
            frame_timing(request).duration_ns() + frame_timing(second).duration_ns());
  EXPECT_LT(received.back().delivery_ns, 2 * kMs);  // 18 frames in well under 2 ms
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    EXPECT_DOUBLE_EQ(firmware.duty()[i], 200.0 / 511.0);
  }
}

TEST(RoverFirmware, RequestsSeeTheShaftWhereItIsWhenTheyArrive) {
  RoverFirmware firmware(wheels_only_params(), exact_sim_truth(Params{}), 1);
  firmware.advance_to(0, MotorVector{}, SensorTruthSample{});
  firmware.send(protocol::encode(protocol::ControlRequest{0, false, true, 0}), 0);
  // The shaft turns 1000 pulses during the first millisecond (from mid-pulse 0.5).
  MotorVector angles{};
  angles[0] = 1000.5 * kRadPerPulse;
  const auto received = firmware.advance_to(kMs, angles, SensorTruthSample{});
  ASSERT_EQ(received.size(), 1U);
  // Delivered at 76 µs: ⌊0.5 + 76⌋ pulses on the straight line.
  EXPECT_EQ(std::get<protocol::ControlResponse>(protocol::decode(received[0].frame).message()).enc,
            76);
}

TEST(RoverFirmware, DeadManStopsAllMotorsOnTime) {
  RoverFirmware firmware(wheels_only_params(), exact_sim_truth(Params{}), 1);
  firmware.send(protocol::encode(protocol::DeadManRequest{2}), 0);
  send_cycle(firmware, 10 * kMs, 300);
  const std::vector<BusDelivery> first = run(firmware, 0, 20 * kMs);
  SimTimeNs last_measurement_ns = -1;
  ASSERT_EQ(firmware.duty()[5], 300.0 / 511.0);
  // The 0x80 reached µ8 when its frame ended; find it from the bus's own timing: it is the
  // last request of the cycle, right before µ8's answer is ready 50 µs later.
  for (const BusDelivery& delivery : first) {
    if (delivery.origin == 8) {
      last_measurement_ns = delivery.ready_ns - 50'000;
    }
  }
  ASSERT_GT(last_measurement_ns, 10 * kMs);
  const SimTimeNs deadline_ns = last_measurement_ns + 2 * 262'144'000;
  std::vector<BusDelivery> stops;
  // The first stop frames, and the repeat one tick later (the silence lasts).
  const SimTimeNs after_repeat_ns = deadline_ns + 262'144'000 + 5 * kMs;
  for (const BusDelivery& delivery : run(firmware, 20 * kMs, after_repeat_ns)) {
    if (delivery.origin == 8) {
      stops.push_back(delivery);
    }
  }
  ASSERT_EQ(stops.size(), 16U);
  EXPECT_EQ(stops[0].ready_ns, deadline_ns);
  EXPECT_EQ(stops[0].start_ns, deadline_ns);  // the bus is idle: SOF at the deadline
  EXPECT_EQ(stops[8].start_ns, deadline_ns + 262'144'000);
  for (std::uint8_t node = 0; node < 16; ++node) {
    EXPECT_EQ(std::get<protocol::ControlRequest>(protocol::decode(stops[node].frame).message()),
              (protocol::ControlRequest{static_cast<std::uint8_t>(node % 8), false, true, 0}));
  }
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    EXPECT_EQ(firmware.duty()[i], 0.0);
  }
  EXPECT_EQ(firmware.sensor_controller().dead_man_stops(), 1U);
  EXPECT_EQ(firmware.sensor_controller().dead_man_firings(), 2U);
}

// Soak seed 734: the bus lost µ8's one stop frame to µ7, which kept its duty through a 30-s
// brown-out. µ8 sends them again every tick while the silence lasts, so the motor stops one tick
// later, and the loss is counted for the soak's dead-man check.
TEST(RoverFirmware, ALostStopFrameReachesItsMotorOneTickLater) {
  RoverFirmware firmware(wheels_only_params(), exact_sim_truth(Params{}), 1);
  firmware.send(protocol::encode(protocol::DeadManRequest{1}), 0);
  send_cycle(firmware, 10 * kMs, 300);
  run(firmware, 0, 20 * kMs);
  ASSERT_EQ(firmware.duty()[5], 300.0 / 511.0);
  const std::optional<SimTimeNs> deadline_ns =
      firmware.sensor_controller().dead_man_deadline_ns();
  ASSERT_TRUE(deadline_ns);
  run(firmware, 20 * kMs, *deadline_ns - kMs);
  EXPECT_EQ(firmware.stop_frames_lost(), (std::array<std::uint64_t, kMotorCount>{}));
  firmware.set_frame_loss_probability(1.0);  // the first stop frames are lost
  run(firmware, *deadline_ns - kMs, *deadline_ns + 5 * kMs);
  firmware.set_frame_loss_probability(0.0);
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    EXPECT_EQ(firmware.stop_frames_lost()[i], 1U) << i;
  }
  EXPECT_EQ(firmware.duty()[5], 300.0 / 511.0);
  run(firmware, *deadline_ns + 5 * kMs, *deadline_ns + 262'144'000 - kMs);
  EXPECT_EQ(firmware.duty()[5], 300.0 / 511.0);
  run(firmware, *deadline_ns + 262'144'000 - kMs, *deadline_ns + 262'144'000 + 5 * kMs);
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    EXPECT_EQ(firmware.duty()[i], 0.0) << i;
    EXPECT_EQ(firmware.stop_frames_lost()[i], 1U) << i;
  }
}

TEST(RoverFirmware, SilentControllerActsButNeverAnswers) {
  RoverFirmware firmware(wheels_only_params(), exact_sim_truth(Params{}), 1);
  firmware.set_silent(3, true);
  send_cycle(firmware, 0, 100);
  const std::vector<BusDelivery> received = run(firmware, 0, 5 * kMs);
  EXPECT_EQ(received.size(), 8U);
  for (const BusDelivery& delivery : received) {
    EXPECT_NE(delivery.origin, 3);
  }
  EXPECT_DOUBLE_EQ(firmware.duty()[3], 100.0 / 511.0);
}

TEST(RoverFirmware, LostFramesReachNobody) {
  RoverFirmware firmware(wheels_only_params(), exact_sim_truth(Params{}), 1);
  firmware.set_frame_loss_probability(1.0);
  send_cycle(firmware, 0, 100);
  EXPECT_TRUE(run(firmware, 0, 5 * kMs).empty());
  EXPECT_EQ(firmware.duty()[0], 0.0);
}

std::vector<BusDelivery> seeded_scenario(std::uint64_t seed) {
  RoverFirmware firmware(wheels_only_params(), make_sim_truth(Params{}, seed), seed);
  firmware.set_frame_loss_probability(0.2);
  firmware.set_lost_pulse_fraction(2, 0.1);
  std::vector<BusDelivery> received;
  for (int cycle = 0; cycle < 64; ++cycle) {
    const SimTimeNs start_ns = SimTimeNs{cycle} * 15'625'000;
    send_cycle(firmware, start_ns, static_cast<std::uint16_t>(4 * cycle));
    for (SimTimeNs t = start_ns + kMs; t <= start_ns + 15 * kMs; t += kMs) {
      MotorVector angles{};
      angles.fill(2.0 * ns_to_seconds(t));
      SensorTruthSample sensors;
      sensors.yaw_rate_radps = 0.1;
      for (const BusDelivery& delivery : firmware.advance_to(t, angles, sensors)) {
        received.push_back(delivery);
      }
    }
  }
  return received;
}

TEST(RoverFirmware, SeededRunIsIdenticalTwice) {
  const std::vector<BusDelivery> a = seeded_scenario(17);
  const std::vector<BusDelivery> b = seeded_scenario(17);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].frame, b[i].frame);
    EXPECT_EQ(a[i].delivery_ns, b[i].delivery_ns);
    EXPECT_TRUE(protocol::decode(a[i].frame).ok());  // every emitted frame is well formed
  }
  EXPECT_GT(a.size(), 64U * 9U / 2U);  // about 0.8 · 0.8 of 576 answers arrive
  EXPECT_LT(a.size(), 64U * 9U);
}

TEST(RoverFirmware, TimeMustNotGoBack) {
  RoverFirmware firmware(wheels_only_params(), exact_sim_truth(Params{}), 1);
  firmware.advance_to(5 * kMs, MotorVector{}, SensorTruthSample{});
  EXPECT_THROW(firmware.advance_to(4 * kMs, MotorVector{}, SensorTruthSample{}),
               std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::sim
