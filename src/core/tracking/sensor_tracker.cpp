#include "core/tracking/sensor_tracker.hpp"

#include <sstream>
#include <stdexcept>
#include <string>

#include "core/tracking/sensor_conversion.hpp"

namespace marsokhod::tracking {
namespace {

const SensorParams& validated(const SensorParams& params) {
  validate(params);
  return params;
}

void require_adc_counts(std::uint16_t counts, const char* name) {
  if (counts > kAdcMaxCounts) {
    std::ostringstream message;
    message << "invalid µ8 reading " << name << " = " << counts
            << ": µ8's converter has 10 bits (0..1023); decode the 0x81 response with the "
               "protocol codec";
    throw std::invalid_argument(message.str());
  }
}

void require_adc_counts(const protocol::MeasurementResponse& response) {
  require_adc_counts(response.yaw, "yaw");
  require_adc_counts(response.acc[0], "acc1");
  require_adc_counts(response.acc[1], "acc2");
  require_adc_counts(response.acc[2], "acc3");
  require_adc_counts(response.tlt, "tlt");
  require_adc_counts(response.vcc, "vcc");
}

}  // namespace

SensorTracker::SensorTracker(const SensorParams& sensors, const FilterParams& filters)
    : sensors_(validated(sensors)),
      gyro_null_(sensors.gyro_null_typ_counts, filters.gyro_null_lambda),
      reference_voltage_(filters.reference_voltage_lambda) {
  state_.gyro_null_counts = gyro_null_.null_counts();
}

const SensorState& SensorTracker::update(const protocol::MeasurementResponse& response,
                                         bool rover_still, bool all_duty_zero) {
  require_adc_counts(response);
  const double yaw_counts = response.yaw;
  state_.yaw_rate_radps =
      yaw_rate_radps(yaw_counts, gyro_null_.null_counts(), sensors_.gyro_radps_per_count);
  state_.gyro_null_counts = gyro_null_.update(yaw_counts, rover_still);

  for (std::size_t i = 0; i < state_.accel_mps2.size(); ++i) {
    state_.accel_mps2[i] =
        accelerometer_mps2(response.acc[i], sensors_.accelerometer[i], sensors_.gravity_mps2);
  }

  const double tilt_counts = response.tlt;
  if (response.tilt_channel == protocol::TiltChannel::kFront) {
    state_.front_tilt_rad = sensors_.tilt_front(tilt_counts);
    state_.front_tilt_seen = true;
  } else {
    state_.rear_tilt_rad = sensors_.tilt_rear(tilt_counts);
    state_.rear_tilt_seen = true;
  }
  state_.latest_tilt_channel = response.tilt_channel;

  state_.supply_v = sensors_.supply(response.vcc);
  state_.reference_supply_v = reference_voltage_.update(state_.supply_v, all_duty_zero);
  ++state_.update_count;
  return state_;
}

}  // namespace marsokhod::tracking
