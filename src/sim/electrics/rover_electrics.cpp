#include "sim/electrics/rover_electrics.hpp"

#include <algorithm>
#include <stdexcept>

namespace marsokhod::sim {
namespace {

std::array<MotorModel, kMotorCount> make_motors(const SimTruth& truth) {
  return {MotorModel(truth.motors[0]), MotorModel(truth.motors[1]), MotorModel(truth.motors[2]),
          MotorModel(truth.motors[3]), MotorModel(truth.motors[4]), MotorModel(truth.motors[5]),
          MotorModel(truth.motors[6]), MotorModel(truth.motors[7])};
}

std::variant<Battery, TetherSupply> make_supply(const PowerTruth& power) {
  if (power.supply == SupplyKind::kTether) {
    return TetherSupply(power.tether);
  }
  return Battery(power.battery);
}

}  // namespace

RoverElectrics::RoverElectrics(const SimTruth& truth)
    : power_(truth.power),
      motors_(make_motors(truth)),
      supply_(make_supply(truth.power)),
      computer_(truth.power.brownout_v, truth.power.reboot_s) {
  // The rover at rest: the base load alone, the motors' lines at d = 0.
  output_.base_load_a = base_load_a();
  output_.total_current_a = output_.base_load_a;
  output_.peak_total_current_a = output_.total_current_a;
  output_.supply_v = supply_voltage_v(output_.total_current_a);
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    const MotorTruth& motor = motors_[i].truth();
    output_.drive.droop_radps_per_nm[i] = droop_radps_per_nm(motor, 0.0, kReferenceIcr, true);
    output_.drive.stall_torque_nm[i] = stall_torque_nm(motor, 0.0, output_.supply_v, kReferenceIcr);
    output_.drive.brake_torque_nm[i] = brake_torque_nm(motor, output_.supply_v, kReferenceIcr);
  }
  if (const Battery* battery = std::get_if<Battery>(&supply_)) {
    output_.state_of_charge = battery->state_of_charge();
  }
}

double RoverElectrics::base_load_a() const {
  return power_.bridge_load_a + power_.controller_load_a +
         (computer_.on() ? power_.computer_load_a : 0.0);
}

double RoverElectrics::supply_step(double current_a, double dt_s) {
  return std::visit([&](auto& supply) { return supply.step(current_a, dt_s); }, supply_);
}

double RoverElectrics::supply_voltage_v(double current_a) const {
  return std::visit([&](const auto& supply) { return supply.terminal_voltage_v(current_a); },
                    supply_);
}

const ElectricsOutput& RoverElectrics::step(const ElectricsInput& input, double dt_s) {
  double total_a = base_load_a();
  output_.base_load_a = total_a;
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    output_.motor_current_a[i] =
        motor_current_a(motors_[i].truth(), previous_duty_[i], previous_icr_[i],
                        input.shaft_torque_nm[i], input.shaft_speed_radps[i]);
    total_a += output_.motor_current_a[i];
  }
  output_.total_current_a = total_a;
  output_.peak_total_current_a = std::max(output_.peak_total_current_a, total_a);
  output_.supply_v = supply_step(total_a, dt_s);
  output_.computer_on = computer_.update(output_.supply_v, dt_s);
  output_.reboot_remaining_s = computer_.off_remaining_s();
  output_.brownout_count = computer_.brownout_count();
  if (const Battery* battery = std::get_if<Battery>(&supply_)) {
    output_.state_of_charge = battery->state_of_charge();
  }
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    const MotorLine line = motors_[i].step(input.duty[i], output_.supply_v, input.icr[i],
                                           input.shaft_speed_radps[i], dt_s);
    output_.drive.no_load_speed_radps[i] = line.no_load_speed_radps;
    output_.drive.droop_radps_per_nm[i] = line.droop_radps_per_nm;
    output_.drive.stall_torque_nm[i] = line.stall_torque_nm;
    output_.drive.brake_torque_nm[i] = line.brake_torque_nm;
  }
  previous_duty_ = input.duty;
  previous_icr_ = input.icr;
  return output_;
}

void RoverElectrics::set_extra_series_resistance_ohm(double resistance_ohm) {
  std::visit([&](auto& supply) { supply.set_extra_resistance_ohm(resistance_ohm); }, supply_);
}

void RoverElectrics::set_tether_voltage(double set_v) {
  TetherSupply* tether = std::get_if<TetherSupply>(&supply_);
  if (tether == nullptr) {
    throw std::invalid_argument("the rover runs on its battery: only a tether's voltage can be set");
  }
  tether->set_voltage(set_v);
}

void RoverElectrics::set_state_of_charge(double state_of_charge) {
  if (Battery* battery = std::get_if<Battery>(&supply_)) {
    battery->set_state_of_charge(state_of_charge);
  }
}

void RoverElectrics::force_brownout() {
  computer_.force_brownout();
  output_.computer_on = false;
  output_.reboot_remaining_s = computer_.off_remaining_s();
  output_.brownout_count = computer_.brownout_count();
}

}  // namespace marsokhod::sim
