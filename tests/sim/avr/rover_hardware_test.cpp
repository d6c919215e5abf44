// The nine firmware images behind RoverFirmware's bus (rover_hardware.hpp): a cycle answered by
// all nine with the emulation's payloads, the duty they set, and µ8's firmware stopping the eight
// motor firmwares over the bus when its dead man's switch fires.
#include "sim/avr/rover_hardware.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <variant>
#include <memory>
#include <string>

#include "core/protocol/codec.hpp"
#include "sim/firmware/rover_firmware.hpp"

namespace marsokhod::sim {
namespace {

constexpr SimTimeNs kMs = 1'000'000;

Params params_at_zero() {
  Params params;
  params.motors.initial_position_rad = {};
  return params;
}

SimTruth noiseless_truth() {
  SimTruth truth = exact_sim_truth(Params{});
  truth.sensors.gyro_drift_amplitude_counts = 0.0;
  truth.sensors.gyro_noise_counts = 0.0;
  truth.sensors.accelerometer_noise_counts = 0.0;
  truth.sensors.tilt_noise_counts = 0.0;
  truth.sensors.supply_noise_counts = 0.0;
  return truth;
}

RoverFirmware on_firmware(const Params& params, const SimTruth& truth) {
  return RoverFirmware(params, truth, 1, SensorTruthSample{},
                       std::make_unique<avr::RoverHardware>(MARSOKHOD_FIRMWARE_DIR, params,
                                                            truth.sensors, 1, SensorTruthSample{}));
}

void send_cycle(RoverFirmware& firmware, SimTimeNs time_ns, std::uint16_t pwm) {
  for (std::uint8_t node = 0; node < 8; ++node) {
    firmware.send(protocol::encode(protocol::ControlRequest{node, false, true, pwm}), time_ns);
  }
  firmware.send(protocol::encode(protocol::MeasurementRequest{}), time_ns);
}

// Motor i turns at (i+1)·0.1 rad/s for the first 40 ms, then stands: the cycles compared below
// come after 40 ms, when no encoder pulse can fall between a request's arrival and the firmware's
// reading of enc (a few µs) or near a slice end of vel (the emulation_test's exact conditions).
MotorVector angles_at(SimTimeNs time_ns) {
  MotorVector angles{};
  const double moving_s = ns_to_seconds(std::min<SimTimeNs>(time_ns, 40 * kMs));
  for (std::size_t i = 0; i < angles.size(); ++i) {
    angles[i] = 0.1 * static_cast<double>(i + 1) * moving_s + 0.3e-4;
  }
  return angles;
}

std::vector<BusDelivery> run(RoverFirmware& firmware, SimTimeNs from_ns, SimTimeNs to_ns) {
  std::vector<BusDelivery> received;
  for (SimTimeNs t = from_ns + kMs; t <= to_ns; t += kMs) {
    for (const BusDelivery& delivery : firmware.advance_to(t, angles_at(t), SensorTruthSample{})) {
      received.push_back(delivery);
    }
  }
  return received;
}

// Answers by controller, tim blanked: the bus orders them differently (the firmware answers in
// about 15 µs, the emulation after its 50 µs), so later requests arrive at other times.
std::map<int, protocol::CanFrame> payloads(const std::vector<BusDelivery>& received) {
  std::map<int, protocol::CanFrame> by_origin;
  for (const BusDelivery& delivery : received) {
    protocol::CanFrame frame = delivery.frame;
    if (delivery.origin < 8) frame.data[0] = frame.data[1] = 0;
    by_origin[delivery.origin] = frame;
  }
  return by_origin;
}

TEST(RoverHardware, CyclesAreAnsweredByAllNineLikeTheEmulation) {
  const Params params = params_at_zero();
  const SimTruth truth = noiseless_truth();
  RoverFirmware emulated(params, truth, 1);
  RoverFirmware real = on_firmware(params, truth);
  for (int cycle = 0; cycle < 4; ++cycle) {
    const SimTimeNs start = (50 + 16 * cycle) * kMs;
    run(emulated, start - kMs, start);
    run(real, start - kMs, start);
    send_cycle(emulated, start, static_cast<std::uint16_t>(100 * cycle));
    send_cycle(real, start, static_cast<std::uint16_t>(100 * cycle));
    const std::vector<BusDelivery> from_emulation = run(emulated, start, start + 15 * kMs);
    const std::vector<BusDelivery> from_firmware = run(real, start, start + 15 * kMs);
    ASSERT_EQ(from_firmware.size(), 9U) << "cycle " << cycle;
    EXPECT_EQ(payloads(from_firmware), payloads(from_emulation)) << "cycle " << cycle;
    const auto decoded = protocol::decode(payloads(from_firmware).at(7));
    // µ7 turned 0.8 rad/s · 40 ms = 0.032 rad, from 0.03 mrad to 32.03 mrad: ⌊32.03e-3 · 115000/2π⌋
    // = ⌊586.2⌋ pulses.
    EXPECT_EQ(std::get<protocol::ControlResponse>(decoded.message()).enc, 586);
  }
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    EXPECT_DOUBLE_EQ(real.duty()[i], 300.0 / 511.0);
    EXPECT_EQ(real.icr()[i], 511);
  }
}

TEST(RoverHardware, SensorFirmwareStopsTheMotorFirmwaresOverTheBus) {
  const Params params = params_at_zero();
  RoverFirmware real = on_firmware(params, noiseless_truth());
  real.send(protocol::encode(protocol::DeadManRequest{1}), 1 * kMs);
  send_cycle(real, 2 * kMs, 400);
  std::vector<BusDelivery> received = run(real, 0, 200 * kMs);
  for (std::size_t i = 0; i < kMotorCount; ++i) EXPECT_DOUBLE_EQ(real.duty()[i], 400.0 / 511.0);
  received = run(real, 200 * kMs, 300 * kMs);
  ASSERT_EQ(received.size(), 16U) << "µ8's eight stop frames and the motors' eight answers";
  std::erase_if(received, [](const BusDelivery& delivery) { return delivery.origin != 8; });
  ASSERT_EQ(received.size(), 8U) << "µ8's eight stop frames";
  for (std::size_t i = 0; i < received.size(); ++i) {
    EXPECT_EQ(received[i].origin, 8);
    EXPECT_EQ(received[i].frame, protocol::encode(protocol::ControlRequest{
                                     static_cast<std::uint8_t>(i), false, true, 0}));
    // The 0x80 reached µ8 at about 2.6 ms; one tick of dog is 262.144 ms.
    EXPECT_GT(received[i].ready_ns, 264 * kMs);
    EXPECT_LT(received[i].ready_ns, 266 * kMs);
  }
  for (std::size_t i = 0; i < kMotorCount; ++i) EXPECT_EQ(real.duty()[i], 0.0) << "motor " << i;
}

TEST(RoverHardware, MissingImagesAreNamed) {
  const Params params = params_at_zero();
  try {
    avr::RoverHardware hardware("/nonexistent", params, SensorTruth{}, 1, SensorTruthSample{});
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/mu8.elf"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace marsokhod::sim
