// One full control cycle, Driver::step: decode 9 responses … encode 9 requests, while driving
// forward and spinning with rolking running (every stage of the cycle busy). The scripted rover
// that answers is outside the timed region. Reports the median and the 99th percentile of the
// per-cycle time over 20 000 cycles, per repetition.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "core/estimation/failsafes.hpp"
#include "core/estimation/null_drift.hpp"
#include "core/estimation/pose_estimator.hpp"
#include "driver/driver.hpp"
#include "scripted_rover.hpp"

namespace marsokhod::driver {
namespace {

// state.range(0) = 1: on the tether (Field Experiment 1.1), where every cycle also bisects D_I
// through the summation, (4.3)'s inverse and the slew rule (behaviour/supply_current.hpp).
void BM_DriverStep(benchmark::State& state) {
  constexpr int kCycles = 20000;
  constexpr double kH = 0.0156;
  for (auto _ : state) {
    const Params params;
    Driver driver(params);
    if (state.range(0) == 1) {
      RuntimeSettings tether = driver.runtime();
      tether.supply = SupplyKind::kTether;
      driver.set_runtime(tether);
    }
    testing::ScriptedRover rover;
    std::vector<protocol::CanFrame> inbox;
    double t = 0.0;
    const OperatorInput input = testing::driving_with_rolking();
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
BENCHMARK(BM_DriverStep)
    ->ArgName("tether")
    ->Arg(0)
    ->Arg(1)
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMicrosecond);

// What issue #15 added to every cycle: the dead reckoning (pose_estimator.hpp), the null drift's
// correction (null_drift.hpp) and the two failsafes (failsafes.hpp), fed a turning drive whose
// inputs change every cycle.
void BM_EstimationCycle(benchmark::State& state) {
  estimation::PoseEstimator pose(0.125);
  estimation::TipOverMonitor tip_over;
  estimation::StuckMonitor stuck;
  estimation::NullDriftCorrection null_drift(0.0170, 64);
  estimation::OdometryInput odometry;
  odometry.period_s = 0.0156;
  estimation::StuckInput wheels;
  wheels.period_s = 0.0156;
  wheels.driving = true;
  wheels.motion_asked = true;
  std::array<double, 3> accel{0.3, -0.2, -9.8};
  double k = 0.0;
  for (auto _ : state) {
    k += 1.0;
    const double wobble = 0.01 * std::sin(k);
    odometry.yaw_rate_radps = 0.2 + wobble;
    odometry.left_angle_rad += (1.0 + wobble) * odometry.period_s;
    odometry.right_angle_rad += (1.2 - wobble) * odometry.period_s;
    odometry.left_no_load_radps = odometry.right_no_load_radps = 1.2;
    odometry.left_load_radps = odometry.right_load_radps = -0.1;
    wheels.no_load_radps = {1.2, 1.2};
    wheels.velocity_radps = {1.0 + wobble, 1.2 - wobble};
    accel[0] = 0.3 + wobble;
    benchmark::DoNotOptimize(pose.update(odometry));
    benchmark::DoNotOptimize(tip_over.update(accel, 0.0156));
    benchmark::DoNotOptimize(stuck.update(wheels));
    // Standing and moving in turns of 2 s, so that anchors form and legs are corrected.
    const bool still = std::fmod(k, 256.0) < 128.0;
    benchmark::DoNotOptimize(null_drift.update(k * 0.0156, 0.0156, 505.0 + wobble, 505.0, still));
  }
}
BENCHMARK(BM_EstimationCycle)->Unit(benchmark::kNanosecond);

}  // namespace
}  // namespace marsokhod::driver
