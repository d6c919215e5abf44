// One full control cycle, Driver::step: decode 9 responses … encode 9 requests, while driving
// forward and spinning with rolking running (every stage of the cycle busy). The scripted rover
// that answers is outside the timed region. Reports the median and the 99th percentile of the
// per-cycle time over 20 000 cycles, per repetition.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "driver/driver.hpp"
#include "scripted_rover.hpp"

namespace marsokhod::driver {
namespace {

void BM_DriverStep(benchmark::State& state) {
  constexpr int kCycles = 20000;
  constexpr double kH = 0.0156;
  for (auto _ : state) {
    const Params params;
    Driver driver(params);
    testing::ScriptedRover rover;
    std::vector<protocol::CanFrame> inbox;
    double t = 0.0;
    OperatorInput input;
    input.targets = mobility::OperatorTargets{};
    input.targets->v1_radps = 1.0;
    input.targets->v2_radps = 0.3;
    input.targets->gait = mobility::Gait::kRolking;
    input.targets->gait_speed = 0.5;
    std::vector<double> step_ns;
    step_ns.reserve(kCycles);
    double total_s = 0.0;
    for (int k = 0; k < kCycles; ++k) {
      const auto start = std::chrono::steady_clock::now();
      const auto& requests = driver.step(t, inbox, &input);
      const auto end = std::chrono::steady_clock::now();
      const double ns = std::chrono::duration<double, std::nano>(end - start).count();
      step_ns.push_back(ns);
      total_s += ns * 1e-9;
      inbox = rover.respond(requests, kH);
      t += kH;
    }
    state.SetIterationTime(total_s / kCycles);
    std::sort(step_ns.begin(), step_ns.end());
    state.counters["p50_us"] = step_ns[kCycles / 2] / 1000.0;
    state.counters["p99_us"] = step_ns[kCycles * 99 / 100] / 1000.0;
    state.counters["max_us"] = step_ns.back() / 1000.0;
  }
}
BENCHMARK(BM_DriverStep)->UseManualTime()->Iterations(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace marsokhod::driver
