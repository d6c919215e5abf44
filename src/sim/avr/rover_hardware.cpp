#include "sim/avr/rover_hardware.hpp"

#include <algorithm>

namespace marsokhod::sim::avr {
namespace {

constexpr std::uint64_t kNoiseStream = 40;  // a stream of its own (rover_firmware.cpp uses 10–38)
// The controllers are on before the onboard computer starts the driver: their start-up (µ8's
// display takes 47 ms) is over at time 0, when the driver's first frames may arrive. Two whole
// periods T(0) = 32.768 ms of the CAN timer: at time 0 tim reads 0 and vel's slices end where the
// emulation's do.
constexpr SimTimeNs kBootNs = 2 * 32'768'000;

std::string image(const std::string& dir, std::size_t controller) {
  return dir + "/mu" + std::to_string(controller) + ".elf";
}

}  // namespace

RoverHardware::RoverHardware(const std::string& firmware_dir, const Params& params,
                             const SensorTruth& sensors, std::uint64_t seed,
                             const SensorTruthSample& initial_sensors)
    : sensor_(image(firmware_dir, kMotorCount), false, kBootNs),
      truth_(sensors),
      front_pot_(sensors.tilt_backlash_rad, initial_sensors.front_tilt_rad),
      rear_pot_(sensors.tilt_backlash_rad, initial_sensors.rear_tilt_rad),
      noise_(derive_seed(seed, kNoiseStream)) {
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    motors_.push_back(std::make_unique<MotorFirmware>(
        image(firmware_dir, i), params.motors.initial_position_rad[i],
        params.motors.encoder_pulses_per_rev, derive_seed(seed, kNoiseStream + 1 + i), kBootNs));
  }
  sensor_.set_inputs(counts(initial_sensors, 0));
}

SensorCounts RoverHardware::counts(const SensorTruthSample& sample, SimTimeNs time_ns) {
  const auto read = [this](double value, double noise_counts) {
    return quantise_adc(value + noise_.normal(0.0, noise_counts));
  };
  front_pot_.update(sample.front_tilt_rad);
  rear_pot_.update(sample.rear_tilt_rad);
  SensorCounts counts;
  counts.yaw = read(gyro_counts(sample.yaw_rate_radps, gyro_null_counts(truth_, ns_to_seconds(time_ns)),
                                truth_.gyro_radps_per_count),
                    truth_.gyro_noise_counts);
  for (std::size_t i = 0; i < counts.acc.size(); ++i) {
    counts.acc[i] = read(accelerometer_counts(sample.accel_mps2[i], truth_.accelerometer[i],
                                              truth_.gravity_mps2),
                         truth_.accelerometer_noise_counts);
  }
  counts.tilt_front = read(conversion_counts(front_pot_.shaft_rad(), truth_.tilt_front),
                           truth_.tilt_noise_counts);
  counts.tilt_rear = read(conversion_counts(rear_pot_.shaft_rad(), truth_.tilt_rear),
                          truth_.tilt_noise_counts);
  counts.vcc = read(conversion_counts(sample.supply_v, truth_.supply), truth_.supply_noise_counts);
  return counts;
}

void RoverHardware::advance(SimTimeNs time_ns, const MotorVector& shaft_angle_rad,
                            const SensorTruthSample& sensors) {
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    motors_[i]->advance(time_ns, shaft_angle_rad[i]);
  }
  if (time_ns > sensor_.controller().time_ns()) {
    sensor_.set_inputs(counts(sensors, time_ns));
    sensor_.advance(time_ns);
  }
}

void RoverHardware::deliver(const protocol::CanFrame& frame) {
  for (auto& motor : motors_) {
    motor->deliver(frame);
  }
  sensor_.deliver(frame);
}

std::vector<HardwareTransmission> RoverHardware::take_transmitted() {
  std::vector<HardwareTransmission> sent;
  for (std::size_t i = 0; i <= kMotorCount; ++i) {
    for (const TimedCanFrame& frame :
         i < kMotorCount ? motors_[i]->take_transmitted() : sensor_.take_transmitted()) {
      sent.push_back({i, frame.time_ns, frame.frame});
    }
  }
  std::stable_sort(sent.begin(), sent.end(), [](const auto& a, const auto& b) {
    return a.ready_ns < b.ready_ns;
  });
  return sent;
}

MotorVector RoverHardware::duty() const {
  MotorVector duty{};
  for (std::size_t i = 0; i < kMotorCount; ++i) duty[i] = motors_[i]->duty();
  return duty;
}

IcrVector RoverHardware::icr() const {
  IcrVector icr{};
  for (std::size_t i = 0; i < kMotorCount; ++i) icr[i] = motors_[i]->icr();
  return icr;
}

void RoverHardware::set_lost_pulse_fraction(std::size_t motor, double fraction) {
  motors_.at(motor)->set_lost_pulse_fraction(fraction);
}

}  // namespace marsokhod::sim::avr
