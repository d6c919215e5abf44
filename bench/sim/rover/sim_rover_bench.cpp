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

// joint_duty: the joint motors' pwm (the wheels' is 200 of 511). At 200 the joints run to their
// stops and push against them, which gives MuJoCo the stops' constraints to solve; at 0 they stay
// locked, as in the bare rover, so that the two seconds simulate the same kind of motion.
void run_rover_seconds(benchmark::State& state, const SimOptions& options, int joint_duty = 200) {
  const Params params;
  SimulatedRover rover(params, options);
  for (std::uint8_t i = 0; i < 8; ++i) {
    rover.send(protocol::encode(protocol::ConfigurationRequest{i, 511, 0, 0}), 0.0);
  }
  double t = 0.0;
  for (auto _ : state) {
    for (int k = 0; k < 64; ++k) {  // one simulated second
      for (std::uint8_t i = 0; i < 8; ++i) {
        const auto pwm = static_cast<std::uint16_t>(i < kWheelCount ? 200 : joint_duty);
        rover.send(protocol::encode(protocol::ControlRequest{i, false, true, pwm}), t);
      }
      rover.send(protocol::encode(protocol::MeasurementRequest{}), t);
      t += 1.0 / 64.0;
      benchmark::DoNotOptimize(rover.advance_to(t));
    }
  }
  state.counters["real_time_factor"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_SimulatedRoverSecond(benchmark::State& state) {
  run_rover_seconds(state, SimOptions{}, static_cast<int>(state.range(0)));
}
BENCHMARK(BM_SimulatedRoverSecond)
    ->ArgName("joint_pwm")
    ->Arg(200)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond);

void BM_BareMjStepSecond(benchmark::State& state) {
  const SimOptions options;
  BareRover rover = bare_rover(options.terrain, options.physics_timestep_s);
  const int steps = static_cast<int>(std::lround(1.0 / options.physics_timestep_s));
  for (auto _ : state) {
    for (int k = 0; k < steps; ++k) step_bare(rover);
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
