#include "sim/firmware/rover_firmware.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "sim/electrics/seeded_random.hpp"

namespace marsokhod::sim {
namespace {

// Streams of the run's seed, one per part, so that each part's draws are independent.
enum Stream : std::uint64_t { kBusStream = 10, kMotorStreamBase = 20, kSensorStream = 30 };

std::vector<MotorController> make_motor_controllers(const Params& params, const SimTruth& truth,
                                                    std::uint64_t seed) {
  std::vector<MotorController> motors;
  motors.reserve(kMotorCount);
  for (std::uint8_t i = 0; i < kMotorCount; ++i) {
    motors.emplace_back(
        i, params.motors.initial_position_rad[i], params.motors.encoder_pulses_per_rev,
        derive_seed(seed, kMotorStreamBase + i), truth.controllers.velocity_window_slices);
  }
  return motors;
}

}  // namespace

RoverFirmware::RoverFirmware(const Params& params, const SimTruth& truth, std::uint64_t seed,
                             const SensorTruthSample& initial_sensors)
    : motors_(make_motor_controllers(params, truth, seed)),
      sensor_(truth.sensors, derive_seed(seed, kSensorStream), initial_sensors),
      bus_(derive_seed(seed, kBusStream)),
      latency_ns_(seconds_to_ns(truth.controllers.response_latency_s)),
      angle_rad_(params.motors.initial_position_rad),
      target_angle_rad_(params.motors.initial_position_rad),
      target_sensors_(initial_sensors) {}

RoverFirmware::RoverFirmware(const Params& params, const SimTruth& truth, std::uint64_t seed,
                             const SensorTruthSample& initial_sensors,
                             std::unique_ptr<ControllerHardware> hardware)
    : RoverFirmware(params, truth, seed, initial_sensors) {
  hardware_ = std::move(hardware);
}

void RoverFirmware::send(const protocol::CanFrame& frame, SimTimeNs ready_ns) {
  bus_.enqueue(frame, ready_ns, kDriverOrigin);
}

void RoverFirmware::move_controllers_to(SimTimeNs time_ns) {
  if (time_ns > time_ns_) {
    const double fraction =
        static_cast<double>(time_ns - time_ns_) / static_cast<double>(target_ns_ - time_ns_);
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      angle_rad_[i] += (target_angle_rad_[i] - angle_rad_[i]) * fraction;
    }
    time_ns_ = time_ns;
  }
  if (hardware_) {
    hardware_->advance(time_ns_, angle_rad_, target_sensors_);
    return;
  }
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    motors_[i].advance(time_ns_, angle_rad_[i]);
  }
  sensor_.advance(time_ns_, target_sensors_);
}

bool RoverFirmware::enqueue_hardware_transmissions() {
  bool enqueued = false;
  for (const HardwareTransmission& sent : hardware_->take_transmitted()) {
    if (!silent_[sent.controller]) {
      bus_.enqueue(sent.frame, sent.ready_ns, static_cast<int>(sent.controller));
      enqueued = true;
    }
  }
  return enqueued;
}

bool RoverFirmware::fire_dead_man_if_due(SimTimeNs until_ns) {
  const std::optional<SimTimeNs> deadline_ns = sensor_.dead_man_deadline_ns();
  if (!deadline_ns || *deadline_ns > until_ns) {
    return false;
  }
  // A frame that wins an arbitration before the deadline goes first; µ8 joins the next one.
  const std::optional<BusDelivery> next = bus_.peek();
  if (next && next->start_ns < *deadline_ns) {
    return false;
  }
  move_controllers_to(std::max(time_ns_, *deadline_ns));
  for (const protocol::CanFrame& frame : sensor_.fire_dead_man()) {
    if (!silent_[kSensorNode]) {
      bus_.enqueue(frame, *deadline_ns, static_cast<int>(kSensorNode));
    }
  }
  return true;
}

void RoverFirmware::answer(std::size_t controller,
                           const std::optional<protocol::CanFrame>& response,
                           SimTimeNs received_ns) {
  if (response && !silent_[controller]) {
    bus_.enqueue(*response, received_ns + latency_ns_, static_cast<int>(controller));
  }
}

void RoverFirmware::deliver(const BusDelivery& delivery) {
  if (hardware_) {
    hardware_->deliver(delivery.frame);
    return;
  }
  const std::uint32_t node = delivery.frame.id >> 7;  // idt = id >> 3, node = idt >> 4
  if (node < kMotorCount) {
    answer(node, motors_[node].receive(delivery.frame), delivery.delivery_ns);
  } else if (node == kSensorNode) {
    answer(node, sensor_.receive(delivery.frame), delivery.delivery_ns);
  }
}

std::vector<BusDelivery> RoverFirmware::advance_to(SimTimeNs time_ns,
                                                   const MotorVector& shaft_angle_rad,
                                                   const SensorTruthSample& sensors) {
  if (time_ns < time_ns_) {
    throw std::invalid_argument("rover firmware: time must not go back (" +
                                std::to_string(time_ns) + " ns < " + std::to_string(time_ns_) +
                                " ns)");
  }
  target_ns_ = time_ns;
  target_angle_rad_ = shaft_angle_rad;
  target_sensors_ = sensors;
  std::vector<BusDelivery> received;
  for (;;) {
    if (!hardware_ && fire_dead_man_if_due(time_ns)) {
      continue;
    }
    const std::optional<BusDelivery> next = bus_.peek();
    if (hardware_) {
      // Run the controllers up to the next arbitration: what they send by then takes part in it.
      move_controllers_to(std::max(time_ns_, next ? std::min(next->start_ns, time_ns) : time_ns));
      if (enqueue_hardware_transmissions()) {
        continue;
      }
    }
    if (!next || next->delivery_ns > time_ns) {
      break;
    }
    const BusDelivery delivery = bus_.pop();
    move_controllers_to(delivery.delivery_ns);
    if (delivery.lost) {
      const std::uint32_t node = delivery.frame.id >> 7;
      if (delivery.origin == static_cast<int>(kSensorNode) && node < kMotorCount) {
        ++stop_frames_lost_[node];
      }
      continue;
    }
    deliver(delivery);
    if (delivery.origin != kDriverOrigin) {
      received.push_back(delivery);
    }
  }
  move_controllers_to(time_ns);
  return received;
}

MotorVector RoverFirmware::duty() const {
  if (hardware_) {
    return hardware_->duty();
  }
  MotorVector duty{};
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    duty[i] = motors_[i].duty();
  }
  return duty;
}

IcrVector RoverFirmware::icr() const {
  if (hardware_) {
    return hardware_->icr();
  }
  IcrVector icr{};
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    icr[i] = motors_[i].registers().icr;
  }
  return icr;
}

void RoverFirmware::set_silent(std::size_t controller, bool silent) {
  silent_.at(controller) = silent;
}

void RoverFirmware::set_frame_loss_probability(double probability) {
  bus_.set_frame_loss_probability(probability);
}

void RoverFirmware::set_lost_pulse_fraction(std::size_t motor, double fraction) {
  motors_.at(motor).set_lost_pulse_fraction(fraction);
  if (hardware_) {
    hardware_->set_lost_pulse_fraction(motor, fraction);
  }
}

}  // namespace marsokhod::sim
