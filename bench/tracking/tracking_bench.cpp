// One tracking update of a whole control cycle: the eight 0xi1 responses of µ0–µ7 and µ8's 0x81.
#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>

#include "core/params.hpp"
#include "core/protocol/messages.hpp"
#include "core/tracking/motor_tracker.hpp"
#include "core/tracking/sensor_tracker.hpp"

namespace {

using marsokhod::kMotorCount;
namespace protocol = marsokhod::protocol;
namespace tracking = marsokhod::tracking;

void BM_TrackingCycle(benchmark::State& state) {
  tracking::AllMotorsTracker motors(marsokhod::MotorParams{});
  tracking::SensorTracker sensors(marsokhod::SensorParams{}, marsokhod::FilterParams{});
  std::array<protocol::ControlResponse, kMotorCount> responses{};
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    responses[i].node = static_cast<std::uint8_t>(i);
    responses[i].vel = 1200;
  }
  protocol::MeasurementResponse measurement{
      505, {279, 251, 376}, 527, 970, protocol::TiltChannel::kFront};
  std::uint32_t cycle = 0;
  for (auto _ : state) {
    // Registers advance as at 64 Hz with ~550 pulses per cycle; a reversal every 16th cycle.
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      protocol::ControlResponse& response = responses[i];
      response.tim = static_cast<std::uint16_t>(response.tim + 31250);
      if (cycle % 16 == 15) {
        response.stp = static_cast<std::uint16_t>(response.enc + 300);
        response.dir = !response.dir;
      }
      response.enc = static_cast<std::uint16_t>(response.enc + 550);
    }
    measurement.tilt_channel =
        cycle % 2 == 0 ? protocol::TiltChannel::kFront : protocol::TiltChannel::kRear;
    const tracking::MotorsSample& motor_sample = motors.update(responses, 0);
    const tracking::SensorState& sensor_state = sensors.update(measurement, cycle % 64 == 0, false);
    benchmark::DoNotOptimize(&motor_sample);
    benchmark::DoNotOptimize(&sensor_state);
    benchmark::ClobberMemory();
    ++cycle;
  }
}
BENCHMARK(BM_TrackingCycle);

}  // namespace
