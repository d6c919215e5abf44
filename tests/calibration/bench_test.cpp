// The simulated bench: the controllers acknowledge, raw duty cycles turn the wheels at the
// simulator's true no-load speed on the stand, the stand turns gravity in the accelerometer's
// axes, the tether's knob sets U, a strapped weight loads its wheel once a revolution.
#include "calibration/bench.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "calibration_test_support.hpp"
#include "sim/rover/simulated_rover.hpp"

namespace marsokhod::calibration {
namespace {

constexpr double kPi = std::numbers::pi;

using testing::config;

BenchSetup stand(double roll = 0.0, double pitch = 0.0) {
  BenchSetup s;
  s.placement = BenchSetup::Placement::kStand;
  s.stand_roll_rad = roll;
  s.stand_pitch_rad = pitch;
  s.instruction = "test stand";
  return s;
}

TEST(SimBench, ControllersAcknowledgeAndTheSourceNamesTheUnit) {
  const Params params = config();
  SimBench bench(params, sim_bench_options(5));
  EXPECT_THROW(bench.cycle(MotorVector{}), BenchError);
  bench.start(params.cycle.icr, params.cycle.con);
  const BenchSample& s = bench.cycle(MotorVector{});
  EXPECT_TRUE(std::all_of(s.fresh.begin(), s.fresh.end(), [](bool f) { return f; }));
  ASSERT_TRUE(s.raw.has_value());
  EXPECT_EQ(bench.source(), "simulator (seed 5, tether)");
  EXPECT_THROW(bench.start(100, 0), std::invalid_argument);
}

TEST(SimBench, RawDutyOnTheStandRunsAtTheTrueNoLoadSpeed) {
  const Params params = config();
  SimBench bench(params, sim_bench_options(5));
  bench.start(params.cycle.icr, params.cycle.con);
  bench.arrange(stand());
  MotorVector duty{};
  for (std::size_t i = 0; i < kWheelCount; ++i) duty[i] = 0.5;
  bench.hold(duty, 3.0);
  // The rules of chapter 3.2 ramp the duty by 0.05 a cycle: it is there long since.
  EXPECT_DOUBLE_EQ(bench.last().duty[0], 0.5);
  const std::vector<BenchSample> samples = bench.hold(duty, 1.0);
  const sim::SimulatedRover& rover = bench.rover();
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    double sum = 0.0;
    for (const BenchSample& s : samples) sum += s.velocity_radps[i];
    const double measured = sum / static_cast<double>(samples.size());
    const double truth = rover.electrics().drive.no_load_speed_radps[i];
    // Free wheels on the stand carry no load: w̄ is the no-load speed, within the encoder's
    // velocity quantisation (2π/115000 per T(con) = 0.0017 rad/s) and the lag's ripple.
    EXPECT_NEAR(measured, truth, 0.01 * truth) << kMotorNames[i];
  }
  bench.stop();
  EXPECT_DOUBLE_EQ(bench.last().duty[0], 0.0);
  EXPECT_LT(std::abs(bench.last().velocity_radps[0]), 0.02);
}

TEST(SimBench, TheStandTurnsGravityIntoEachAccelerometerAxis) {
  const Params params = config();
  sim::SimOptions options = sim_bench_options(5);
  options.nominal_unit = true;  // the configured ±g table converts exactly
  SimBench bench(params, options);
  bench.start(params.cycle.icr, params.cycle.con);
  struct Case {
    double roll, pitch;
    std::array<double, 3> gravity;  // gravity in the sensor axes x1 forward, x2 left, x3 up
  };
  const double g = params.sensors.gravity_mps2;
  for (const Case& c : {Case{0.0, 0.0, {0, 0, -g}}, Case{kPi / 2, 0.0, {0, -g, 0}},
                        Case{-kPi / 2, 0.0, {0, g, 0}}, Case{0.0, kPi / 2, {g, 0, 0}},
                        Case{0.0, -kPi / 2, {-g, 0, 0}}, Case{kPi, 0.0, {0, 0, g}}}) {
    bench.arrange(stand(c.roll, c.pitch));
    std::array<double, 3> sum{};
    const std::vector<BenchSample> samples = bench.hold(MotorVector{}, 1.0);
    for (const BenchSample& s : samples) {
      for (int a = 0; a < 3; ++a) sum[a] += s.sensors.accel_mps2[a];
    }
    for (int a = 0; a < 3; ++a) {
      // Noise 0.7 counts averaged over 64 readings; one count is 2g/268 = 0.073 m/s².
      EXPECT_NEAR(sum[a] / static_cast<double>(samples.size()), c.gravity[a], 0.1)
          << "roll " << c.roll << " pitch " << c.pitch << " axis x" << a + 1;
    }
  }
  bench.arrange(BenchSetup{});
  EXPECT_FALSE(bench.rover().on_stand());
}

TEST(SimBench, TheTethersKnobSetsTheSupplyVoltage) {
  const Params params = config();
  sim::SimOptions options = sim_bench_options(5);
  options.nominal_unit = true;
  SimBench bench(params, options);
  bench.start(params.cycle.icr, params.cycle.con);
  BenchSetup setup;
  setup.supply_v = 21.0;
  bench.arrange(setup);
  const BenchSample& s = bench.cycle(MotorVector{});
  // 1.05 A of base load through the tether's 0.1 Ω.
  EXPECT_NEAR(bench.measure_supply_v(), 21.0 - 1.05 * 0.1, 0.01);
  EXPECT_NEAR(s.sensors.supply_v, bench.measure_supply_v(), 0.1);  // ±1.5 counts
  setup.supply_v = 31.0;
  EXPECT_THROW(bench.arrange(setup), std::invalid_argument);
}

TEST(SimBench, AStrappedWeightLoadsItsWheelOnceARevolution) {
  const Params params = config();
  SimBench bench(params, sim_bench_options(5));
  bench.start(params.cycle.icr, params.cycle.con);
  BenchSetup setup = stand();
  setup.weight_wheel = kFrontLeft;
  setup.weight_peak_torque_nm = 5.51;  // Procedure 4.13
  bench.arrange(setup);
  MotorVector duty{};
  duty[kFrontLeft] = duty[kFrontRight] = 0.4;
  bench.hold(duty, 2.0);
  // One revolution at ≈ 1.2 rad/s takes ≈ 5 s.
  const std::vector<BenchSample> samples = bench.hold(duty, 6.0);
  auto spread = [&](std::size_t wheel) {
    double lo = 1e9, hi = -1e9;
    for (const BenchSample& s : samples) {
      lo = std::min(lo, s.velocity_radps[wheel]);
      hi = std::max(hi, s.velocity_radps[wheel]);
    }
    return hi - lo;
  };
  // (4.7): l ≈ τ·B with B ≈ 0.030 (driven along) and 0.015 (braking): the speed swings by about
  // 5.51·(0.030 + 0.015) = 0.25 rad/s on the loaded wheel and not at all on the other.
  EXPECT_GT(spread(kFrontLeft), 0.15);
  EXPECT_LT(spread(kFrontRight), 0.05);
  EXPECT_GT(spread(kFrontLeft), 4.0 * spread(kFrontRight));
}

}  // namespace
}  // namespace marsokhod::calibration
