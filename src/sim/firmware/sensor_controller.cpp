#include "sim/firmware/sensor_controller.hpp"

#include <cstdio>
#include <variant>

#include "core/protocol/codec.hpp"

namespace marsokhod::sim {

SensorController::SensorController(const SensorTruth& truth, std::uint64_t seed,
                                   const SensorTruthSample& initial)
    : truth_(truth),
      random_(seed),
      sample_(initial),
      front_pot_(truth.tilt_backlash_rad, initial.front_tilt_rad),
      rear_pot_(truth.tilt_backlash_rad, initial.rear_tilt_rad) {}

void SensorController::advance(SimTimeNs time_ns, const SensorTruthSample& sample) {
  time_ns_ = time_ns;
  sample_ = sample;
  front_pot_.update(sample.front_tilt_rad);
  rear_pot_.update(sample.rear_tilt_rad);
}

protocol::MeasurementResponse SensorController::measure() {
  const auto read = [this](double counts, double noise_counts) {
    return quantise_adc(counts + random_.normal(0.0, noise_counts));
  };
  protocol::MeasurementResponse response;
  const double null_counts = gyro_null_counts(truth_, ns_to_seconds(time_ns_));
  response.yaw = read(gyro_counts(sample_.yaw_rate_radps, null_counts, truth_.gyro_radps_per_count),
                      truth_.gyro_noise_counts);
  for (std::size_t i = 0; i < response.acc.size(); ++i) {
    response.acc[i] = read(
        accelerometer_counts(sample_.accel_mps2[i], truth_.accelerometer[i], truth_.gravity_mps2),
        truth_.accelerometer_noise_counts);
  }
  response.tilt_channel = next_channel_;
  const bool front = next_channel_ == protocol::TiltChannel::kFront;
  response.tlt = read(front ? conversion_counts(front_pot_.shaft_rad(), truth_.tilt_front)
                            : conversion_counts(rear_pot_.shaft_rad(), truth_.tilt_rear),
                      truth_.tilt_noise_counts);
  response.vcc =
      read(conversion_counts(sample_.supply_v, truth_.supply), truth_.supply_noise_counts);
  next_channel_ = front ? protocol::TiltChannel::kRear : protocol::TiltChannel::kFront;
  last_measurement_ = response;
  return response;
}

std::optional<protocol::CanFrame> SensorController::receive(const protocol::CanFrame& frame) {
  if ((frame.id >> 7) != protocol::kSensorController) {
    return std::nullopt;  // the acceptance filter passes idt 0x8T only
  }
  const protocol::DecodeResult decoded = protocol::decode(frame);
  if (!decoded) {
    return std::nullopt;
  }
  if (const auto* request = std::get_if<protocol::MeasurementRequest>(&decoded.message())) {
    led0_ = request->led0;
    led1_ = request->led1;
    lcd_ = request->lcd;
    last_request_ns_ = time_ns_;
    dead_man_start_ns_ = time_ns_;
    dead_man_overflows_ = 0;
    return protocol::encode(measure());
  }
  if (const auto* dead_man = std::get_if<protocol::DeadManRequest>(&decoded.message())) {
    if (dog_ == 0 && dead_man->dog > 0) {
      dead_man_start_ns_ = time_ns_;
      dead_man_overflows_ = 0;
    }
    dog_ = dead_man->dog;
    return protocol::encode(protocol::DeadManResponse{});
  }
  return std::nullopt;
}

std::optional<SimTimeNs> SensorController::dead_man_deadline_ns() const {
  if (dog_ == 0) {
    return std::nullopt;
  }
  return dead_man_start_ns_ + (dog_ + dead_man_overflows_) * kDeadManPeriodNs;
}

std::array<protocol::CanFrame, 8> SensorController::fire_dead_man() {
  std::array<protocol::CanFrame, 8> frames;
  for (std::uint8_t node = 0; node < frames.size(); ++node) {
    // eim = 1: the driver's own rule for pwm/icr < 0.6 (encoder_interrupt.hpp).
    frames[node] = protocol::encode(protocol::ControlRequest{node, false, true, 0});
  }
  if (dead_man_overflows_ == 0) ++dead_man_stops_;
  ++dead_man_overflows_;
  ++dead_man_firings_;
  return frames;
}

std::string SensorController::lcd_display() const {
  if (!last_request_ns_ || !last_measurement_ || time_ns_ - *last_request_ns_ > kLcdIdleAfterNs) {
    return kLcdIdleText;
  }
  char voltage[16];
  // The firmware knows only its own reading, converted with its constants.
  std::snprintf(voltage, sizeof voltage, "%7.2fV", truth_.supply(last_measurement_->vcc));
  return std::string(lcd_.begin(), lcd_.end()) + voltage;
}

}  // namespace marsokhod::sim
