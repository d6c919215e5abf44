#include "sim/rover/simulated_rover.hpp"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "sim/avr/rover_hardware.hpp"

namespace marsokhod::sim {
namespace {

SimTruth truth_for(const Params& nominal, const SimOptions& options) {
  SimTruth truth = options.unit           ? *options.unit
                   : options.nominal_unit ? exact_sim_truth(nominal)
                                          : make_sim_truth(nominal, options.seed);
  truth.power.supply = options.supply;
  return truth;
}

SensorTruthSample sample_of(const ImuTruth& imu, double supply_v) {
  SensorTruthSample s;
  s.accel_mps2 = imu.accel_mps2;
  s.yaw_rate_radps = imu.yaw_rate_radps;
  s.front_tilt_rad = imu.front_tilt_rad;
  s.rear_tilt_rad = imu.rear_tilt_rad;
  s.supply_v = supply_v;
  return s;
}

void require_fraction(double value, const std::string& name) {
  if (!(value >= 0.0 && value <= 1.0)) {
    throw std::invalid_argument(name + ": " + std::to_string(value) +
                                " is out of range; allowed [0, 1]");
  }
}

// The physics' gaps are the unit's true backlash, not the configured one (Procedure 4.1).
Params with_true_backlash(Params params, const SimTruth& truth) {
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    params.motors.backlash_rad[i] = truth.motors[i].backlash_rad;
  }
  return params;
}

Params with_shaft_angles(Params params, const MotorVector& shaft_angle_rad) {
  params.motors.initial_position_rad = shaft_angle_rad;
  return params;
}

RoverFirmware make_firmware(const Params& params, const SimTruth& truth, const SimOptions& options,
                            const SensorTruthSample& initial_sensors) {
  if (options.firmware_dir.empty()) {
    return RoverFirmware(params, truth, options.seed, initial_sensors);
  }
  return RoverFirmware(params, truth, options.seed, initial_sensors,
                       std::make_unique<avr::RoverHardware>(options.firmware_dir, params,
                                                            truth.sensors, options.seed,
                                                            initial_sensors));
}

}  // namespace

SimulatedRover::SimulatedRover(const Params& nominal, const SimOptions& options)
    : params_(&nominal),
      truth_(truth_for(nominal, options)),
      physics_(with_true_backlash(nominal, truth_), options.terrain, options.physics_timestep_s),
      firmware_params_(with_shaft_angles(nominal, physics_.shaft_angle_rad())),
      electrics_(truth_),
      firmware_(make_firmware(firmware_params_, truth_, options,
                              sample_of(physics_.imu(), electrics_.output().supply_v > 0.0
                                                            ? electrics_.output().supply_v
                                                            : nominal.motors.nominal_supply_v))) {}

double SimulatedRover::time_s() const { return physics_.time_s(); }

void SimulatedRover::send(const protocol::CanFrame& frame, double time_s) {
  if (!computer_on()) {
    ++dropped_;
    return;
  }
  firmware_.send(frame, std::max(seconds_to_ns(time_s), firmware_.time_ns()));
}

SensorTruthSample SimulatedRover::sensor_sample() const {
  const double supply = electrics_.output().supply_v > 0.0 ? electrics_.output().supply_v
                                                           : params_->motors.nominal_supply_v;
  return sample_of(physics_.imu(), supply);
}

void SimulatedRover::physics_step() {
  const double dt = physics_.timestep_s();
  const ElectricsInput input{firmware_.duty(), firmware_.icr(), physics_.shaft_velocity_radps(),
                             physics_.shaft_torque_nm()};
  const ElectricsOutput& e = electrics_.step(input, dt);
  physics_.set_drive({e.drive.no_load_speed_radps, e.drive.droop_radps_per_nm,
                      e.drive.stall_torque_nm, e.drive.brake_torque_nm});
  physics_.step();
  energy_j_ += e.supply_v * e.total_current_a * dt;
  ++steps_;
}

std::vector<TimedFrame> SimulatedRover::advance_to(double time_s) {
  const SimTimeNs target_ns = seconds_to_ns(time_s);
  const SimTimeNs step_ns = seconds_to_ns(physics_.timestep_s());
  std::vector<TimedFrame> out;
  auto collect = [&](const std::vector<BusDelivery>& deliveries) {
    if (!computer_on()) return;  // the onboard computer is down: nobody receives
    for (const BusDelivery& d : deliveries) out.push_back({ns_to_seconds(d.delivery_ns), d.frame});
  };
  // Each physics step starts with the controllers seeing the state at its beginning.
  while (static_cast<SimTimeNs>(steps_ + 1) * step_ns <= target_ns) {
    const SimTimeNs now_ns = static_cast<SimTimeNs>(steps_) * step_ns;
    if (now_ns >= firmware_.time_ns()) {
      collect(firmware_.advance_to(now_ns, physics_.shaft_angle_rad(), sensor_sample()));
    }
    physics_step();
  }
  if (target_ns >= firmware_.time_ns()) {
    collect(firmware_.advance_to(target_ns, physics_.shaft_angle_rad(), sensor_sample()));
  }
  return out;
}

void SimulatedRover::set_faults(const SimFaults& faults) {
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    require_fraction(faults.lost_pulse_fraction[i],
                     "lost_pulse_fraction[" + std::to_string(i) + "]");
  }
  require_fraction(faults.frame_loss_probability, "frame_loss_probability");
  if (!(faults.extra_series_resistance_ohm >= 0.0 && faults.extra_series_resistance_ohm <= 100.0)) {
    throw std::invalid_argument("extra_series_resistance_ohm: " +
                                std::to_string(faults.extra_series_resistance_ohm) +
                                " is out of range; allowed [0, 100] Ω");
  }
  for (std::size_t w = 0; w < kWheelCount; ++w) {
    physics_.set_wheel_blocked(w, faults.wheel_blocked[w]);
    physics_.set_wheel_contact(w, !faults.wheel_no_contact[w]);
  }
  for (std::size_t j = 0; j < 2; ++j) physics_.set_joint_jammed(j, faults.joint_jammed[j]);
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    firmware_.set_lost_pulse_fraction(i, faults.lost_pulse_fraction[i]);
  }
  for (std::size_t c = 0; c <= kMotorCount; ++c) firmware_.set_silent(c, faults.silent[c]);
  firmware_.set_frame_loss_probability(faults.frame_loss_probability);
  electrics_.set_extra_series_resistance_ohm(faults.extra_series_resistance_ohm);
  faults_ = faults;
}

}  // namespace marsokhod::sim
