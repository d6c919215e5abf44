#include "sim/electrics/sim_truth.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace marsokhod::sim {
namespace {

TEST(SimTruth, ExactTruthTakesTheConfiguredUnitValues) {
  const Params params;
  const SimTruth truth = exact_sim_truth(params);
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    EXPECT_EQ(truth.motors[i].scale, params.motors.scale[i]);
    EXPECT_EQ(truth.motors[i].lag_time_constant_s, 0.012);
  }
  EXPECT_EQ(truth.sensors.gyro_null_base_counts, 505.0);
  EXPECT_EQ(truth.sensors.accelerometer[2].plus_g_counts, 376.0);
  EXPECT_EQ(truth.sensors.supply.gain, params.sensors.supply.gain);
  EXPECT_EQ(truth.power.brownout_v, 19.5);
}

TEST(SimTruth, SeededTruthScattersAroundTheNominal) {
  const Params params;
  const SimTruth truth = make_sim_truth(params, 2008);
  int differing_scales = 0;
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    const double nominal = params.motors.scale[i];
    EXPECT_LE(std::abs(truth.motors[i].scale / nominal - 1.0), 0.02) << "motor " << i;
    differing_scales += truth.motors[i].scale != nominal ? 1 : 0;
    EXPECT_GE(truth.motors[i].lag_time_constant_s, 0.010);
    EXPECT_LE(truth.motors[i].lag_time_constant_s, 0.014);
  }
  EXPECT_EQ(differing_scales, 8);  // calibration has something to find on every motor
  EXPECT_LE(std::abs(truth.sensors.gyro_null_base_counts - 505.0), 5.0);
  for (std::size_t axis = 0; axis < 3; ++axis) {
    EXPECT_LE(std::abs(truth.sensors.accelerometer[axis].plus_g_counts -
                       params.sensors.accelerometer[axis].plus_g_counts),
              2.0);
  }
}

TEST(SimTruth, GyroDriftStaysInTheDatasheetWindow) {
  for (std::uint64_t seed = 0; seed < 50; ++seed) {
    const SensorTruth sensors = make_sim_truth(Params{}, seed).sensors;
    // Peak to peak 2A ≤ 5 LSB, fastest rate A·2π/P ≤ 0.01 LSB/s (chapter 3.3).
    EXPECT_LE(2.0 * sensors.gyro_drift_amplitude_counts, 5.0);
    EXPECT_LE(
        sensors.gyro_drift_amplitude_counts * 2.0 * std::numbers::pi / sensors.gyro_drift_period_s,
        0.01);
  }
}

TEST(SimTruth, EqualSeedsGiveEqualTruths) {
  const SimTruth a = make_sim_truth(Params{}, 77);
  const SimTruth b = make_sim_truth(Params{}, 77);
  const SimTruth c = make_sim_truth(Params{}, 78);
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    EXPECT_EQ(a.motors[i].scale, b.motors[i].scale);
    EXPECT_EQ(a.motors[i].dead_zone_v, b.motors[i].dead_zone_v);
  }
  EXPECT_EQ(a.sensors.gyro_drift_phase_rad, b.sensors.gyro_drift_phase_rad);
  EXPECT_NE(a.motors[0].scale, c.motors[0].scale);
}

}  // namespace
}  // namespace marsokhod::sim
