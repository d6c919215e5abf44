// The whole simulated rover (physics + electrics + firmware + bus) per simulated second while a
// driver's full cycle of traffic runs at 64 Hz, against a second of bare mj_step on the same
// model in the same run (BM_BareMjStepSecond; the stack's cost is the ratio of the two).
// real_time_factor = simulated seconds per wall second.
#include <benchmark/benchmark.h>

#include <cmath>

#include "bare_rover.hpp"
#include "core/protocol/codec.hpp"
#include "sim/rover/simulated_rover.hpp"

namespace marsokhod::sim {
namespace {

void run_rover_seconds(benchmark::State& state, const SimOptions& options) {
  const Params params;
  SimulatedRover rover(params, options);
  for (std::uint8_t i = 0; i < 8; ++i) {
    rover.send(protocol::encode(protocol::ConfigurationRequest{i, 511, 0, 0}), 0.0);
  }
  double t = 0.0;
  for (auto _ : state) {
    for (int k = 0; k < 64; ++k) {  // one simulated second
      for (std::uint8_t i = 0; i < 8; ++i) {
        rover.send(protocol::encode(protocol::ControlRequest{i, false, true, 200}), t);
      }
      rover.send(protocol::encode(protocol::MeasurementRequest{}), t);
      t += 1.0 / 64.0;
      benchmark::DoNotOptimize(rover.advance_to(t));
    }
  }
  state.counters["real_time_factor"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_SimulatedRoverSecond(benchmark::State& state) { run_rover_seconds(state, SimOptions{}); }
BENCHMARK(BM_SimulatedRoverSecond)->Unit(benchmark::kMillisecond);

void BM_BareMjStepSecond(benchmark::State& state) {
  const SimOptions options;
  const BareRover rover = bare_rover(options.terrain, options.physics_timestep_s);
  const int steps = static_cast<int>(std::lround(1.0 / options.physics_timestep_s));
  for (auto _ : state) {
    for (int k = 0; k < steps; ++k) mj_step(rover.model.get(), rover.data.get());
  }
  state.counters["real_time_factor"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BareMjStepSecond)->Unit(benchmark::kMillisecond);

// The same with the nine controllers' real firmware in simavr (sim/avr, docs/firmware.md).
void BM_SimulatedRoverSecondOnFirmware(benchmark::State& state) {
  SimOptions options;
  options.firmware_dir = MARSOKHOD_FIRMWARE_DIR;
  run_rover_seconds(state, options);
}
BENCHMARK(BM_SimulatedRoverSecondOnFirmware)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace marsokhod::sim
