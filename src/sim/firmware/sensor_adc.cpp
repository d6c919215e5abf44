#include "sim/firmware/sensor_adc.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace marsokhod::sim {

double gyro_null_counts(const SensorTruth& truth, double time_s) {
  return truth.gyro_null_base_counts +
         truth.gyro_drift_amplitude_counts *
             std::sin(2.0 * std::numbers::pi * time_s / truth.gyro_drift_period_s +
                      truth.gyro_drift_phase_rad);
}

double gyro_counts(double yaw_rate_radps, double null_counts, double radps_per_count) {
  return null_counts - yaw_rate_radps / radps_per_count;
}

double accelerometer_counts(double accel_mps2, const AccelerometerAxisParams& axis,
                            double gravity_mps2) {
  const double span_counts = axis.plus_g_counts - axis.minus_g_counts;
  return 0.5 * (axis.plus_g_counts + axis.minus_g_counts) -
         accel_mps2 * span_counts / (2.0 * gravity_mps2);
}

double conversion_counts(double physical, const LinearConversion& conversion) {
  return (physical - conversion.offset) / conversion.gain;
}

std::uint16_t quantise_adc(double counts) {
  if (!(counts > 0.0)) {
    return 0;  // also NaN: a dead input reads as ground
  }
  return static_cast<std::uint16_t>(std::min(std::floor(counts + 0.5), 1023.0));
}

double PotentiometerBacklash::update(double tilt_rad) {
  shaft_rad_ = std::clamp(shaft_rad_, tilt_rad - half_play_rad_, tilt_rad + half_play_rad_);
  return shaft_rad_;
}

}  // namespace marsokhod::sim
