#include "sim/firmware/sensor_adc.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/tracking/sensor_conversion.hpp"

namespace marsokhod::sim {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(SimSensorAdc, TypicalStateGivesTheTypColumn) {
  const SensorTruth truth = exact_sim_truth(Params{}).sensors;
  // Chapter 3.3's TYP: rest on flat ground, joints equally inclined, 24.57 V.
  EXPECT_EQ(gyro_counts(0.0, truth.gyro_null_base_counts, truth.gyro_radps_per_count), 505.0);
  EXPECT_NEAR(accelerometer_counts(0.0, truth.accelerometer[0], 9.81), 279.0, 1e-12);
  EXPECT_NEAR(accelerometer_counts(0.0, truth.accelerometer[1], 9.81), 251.5, 1e-12);
  EXPECT_NEAR(accelerometer_counts(-9.81, truth.accelerometer[2], 9.81), 376.0, 1e-12);
  EXPECT_EQ(quantise_adc(conversion_counts(24.57, truth.supply)), 970);
  EXPECT_EQ(quantise_adc(conversion_counts(0.0, truth.tilt_front)), 527);
  EXPECT_EQ(quantise_adc(conversion_counts(0.0, truth.tilt_rear)), 521);  // TYP 520: θr = 0.005
}

TEST(SimSensorAdc, InversesOfTheDriversConversions) {
  const Params params;
  for (double a = -14.0; a <= 14.0; a += 0.7) {
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const AccelerometerAxisParams& calibration = params.sensors.accelerometer[axis];
      EXPECT_NEAR(tracking::accelerometer_mps2(accelerometer_counts(a, calibration, 9.81),
                                               calibration, 9.81),
                  a, 1e-12);
    }
  }
  for (double rate = -3.0; rate <= 3.0; rate += 0.25) {
    EXPECT_NEAR(tracking::yaw_rate_radps(gyro_counts(rate, 505.0, 0.0170), 505.0, 0.0170), rate,
                1e-12);
  }
  EXPECT_NEAR(params.sensors.supply(conversion_counts(21.3, params.sensors.supply)), 21.3, 1e-12);
  EXPECT_NEAR(params.sensors.tilt_rear(conversion_counts(-0.4, params.sensors.tilt_rear)), -0.4,
              1e-12);
}

TEST(SimSensorAdc, QuantisationRoundsAndClamps) {
  EXPECT_EQ(quantise_adc(504.5), 505);
  EXPECT_EQ(quantise_adc(504.49), 504);
  EXPECT_EQ(quantise_adc(1023.6), 1023);
  EXPECT_EQ(quantise_adc(5000.0), 1023);
  EXPECT_EQ(quantise_adc(-3.0), 0);
  EXPECT_EQ(quantise_adc(std::nan("")), 0);
}

TEST(SimSensorAdc, PotentiometerFollowsOnlyAfterThePlay) {
  PotentiometerBacklash pot(8.0 * kDeg, 0.0);
  EXPECT_EQ(pot.update(3.0 * kDeg), 0.0);                   // inside ±4°
  EXPECT_NEAR(pot.update(10.0 * kDeg), 6.0 * kDeg, 1e-15);  // dragged at the edge
  EXPECT_NEAR(pot.update(5.0 * kDeg), 6.0 * kDeg, 1e-15);   // reversed: the play first
  EXPECT_NEAR(pot.update(-2.0 * kDeg), 2.0 * kDeg, 1e-15);  // 8° of play crossed, then along
  EXPECT_NEAR(pot.update(-1.0 * kDeg), 2.0 * kDeg, 1e-15);
}

TEST(SimSensorAdc, GyroNullDriftsSlowlyWithinItsWindow) {
  const SensorTruth truth = make_sim_truth(Params{}, 31).sensors;
  double previous = gyro_null_counts(truth, 0.0);
  for (double t = 1.0; t <= 7200.0; t += 1.0) {
    const double null_counts = gyro_null_counts(truth, t);
    EXPECT_LE(std::abs(null_counts - truth.gyro_null_base_counts), 2.5);
    EXPECT_LE(std::abs(null_counts - previous), 0.01);  // ≤ 0.01 LSB/s
    previous = null_counts;
  }
}

}  // namespace
}  // namespace marsokhod::sim
