#include "core/tracking/sensor_conversion.hpp"

#include <string>

#include "core/checks/checks.hpp"

namespace marsokhod::tracking {

void validate(const SensorParams& params) {
  constexpr double kAdcMax = kAdcMaxCounts;
  checks::setting::require_positive(params.gravity_mps2, "sensors.gravity_mps2");
  checks::setting::require_positive(params.gyro_radps_per_count, "sensors.gyro_radps_per_count");
  checks::setting::require_in_range(params.gyro_null_typ_counts, 0.0, kAdcMax,
                           "sensors.gyro_null_typ_counts");
  for (std::size_t i = 0; i < params.accelerometer.size(); ++i) {
    const AccelerometerAxisParams& axis = params.accelerometer[i];
    const std::string index = "[" + std::to_string(i) + "]";
    checks::setting::require_in_range(axis.minus_g_counts, 0.0, kAdcMax,
                             "sensors.accelerometer_minus_g_counts" + index);
    checks::setting::require_in_range(axis.plus_g_counts, 0.0, kAdcMax,
                             "sensors.accelerometer_plus_g_counts" + index);
    // Equal readings would divide (3.5) by zero: Procedure 3.3 was not carried out on this axis.
    checks::setting::require_nonzero(axis.plus_g_counts - axis.minus_g_counts,
                            "sensors.accelerometer_plus_g_counts" + index +
                                " − sensors.accelerometer_minus_g_counts" + index);
  }
  checks::setting::require_nonzero(params.tilt_front.gain, "sensors.tilt_front_rad_per_count");
  checks::setting::require_finite(params.tilt_front.offset, "sensors.tilt_front_offset_rad");
  checks::setting::require_nonzero(params.tilt_rear.gain, "sensors.tilt_rear_rad_per_count");
  checks::setting::require_finite(params.tilt_rear.offset, "sensors.tilt_rear_offset_rad");
  checks::setting::require_positive(params.supply.gain, "sensors.supply_v_per_count");
  checks::setting::require_finite(params.supply.offset, "sensors.supply_offset_v");
}

double yaw_rate_radps(double yaw_counts, double gyro_null_counts, double radps_per_count) {
  return radps_per_count * (gyro_null_counts - yaw_counts);
}

double accelerometer_mps2(double acc_counts, const AccelerometerAxisParams& axis,
                          double gravity_mps2) {
  return gravity_mps2 * (axis.plus_g_counts + axis.minus_g_counts - 2.0 * acc_counts) /
         (axis.plus_g_counts - axis.minus_g_counts);
}

}  // namespace marsokhod::tracking
