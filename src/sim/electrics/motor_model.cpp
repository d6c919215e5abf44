#include "sim/electrics/motor_model.hpp"

#include <algorithm>
#include <cmath>

namespace marsokhod::sim {
namespace {

// (icr+1)/512: the PWM period relative to the reference 15.625 kHz.
double period_ratio(int icr) { return (icr + 1.0) / (kReferenceIcr + 1.0); }

double sign_of(double value) { return value > 0.0 ? 1.0 : (value < 0.0 ? -1.0 : 0.0); }

}  // namespace

double effective_voltage_v(const MotorTruth& motor, double duty, double supply_v, int icr) {
  // Longer PWM pulses (higher icr) break the static friction at smaller average voltage.
  const double dead_zone_v =
      motor.dead_zone_v * std::pow(1.0 / period_ratio(icr), motor.dead_zone_icr_exponent);
  return std::max(0.0, std::abs(duty) * supply_v - dead_zone_v);
}

double steady_no_load_speed_radps(const MotorTruth& motor, double duty, double supply_v, int icr) {
  const double gain = motor.speed_per_volt_radps_per_v *
                      (1.0 + motor.speed_gain_per_icr_octave * std::log2(period_ratio(icr)));
  const double linear_radps = gain * effective_voltage_v(motor, duty, supply_v, icr);
  const double speed_radps = linear_radps / (1.0 + linear_radps / motor.saturation_speed_radps);
  return sign_of(duty) * motor.scale * speed_radps;
}

double droop_radps_per_nm(const MotorTruth& motor, double duty, int icr, bool same_sign) {
  const double base =
      same_sign ? motor.droop_same_sign_radps_per_nm : motor.droop_opposite_sign_radps_per_nm;
  const double low_duty = std::max(0.0, 1.0 - std::abs(duty) / motor.droop_low_duty);
  return base * (1.0 + motor.droop_low_duty_gain * low_duty / period_ratio(icr));
}

double stall_torque_nm(const MotorTruth& motor, double duty, double supply_v, int icr) {
  return std::max(motor.holding_torque_nm, motor.stall_torque_per_volt_nm_per_v *
                                               effective_voltage_v(motor, duty, supply_v, icr));
}

double brake_torque_nm(const MotorTruth& motor, double supply_v, int icr) {
  return stall_torque_nm(motor, 1.0, supply_v, icr);
}

double motor_current_a(const MotorTruth& motor, double duty, int icr, double torque_nm,
                       double shaft_speed_radps) {
  if (duty == 0.0) {
    return 0.0;  // pwm = 0: the bridge does not switch and draws nothing from the supply
  }
  // Lower PWM frequency, larger current ripple: more loss at the same torque (Remark 3.2).
  const double no_load_a =
      motor.no_load_current_a *
          std::max(0.0, 1.0 + motor.current_gain_per_icr_octave * std::log2(period_ratio(icr))) +
      motor.no_load_current_a_per_radps * std::abs(shaft_speed_radps);
  // The motor's current |τ|/k_t flows from the supply only while the bridge conducts, a share
  // |d| of each PWM period; in the rest it circulates through the bridge's freewheeling path
  // (the bridge is a buck converter: U·I_supply = |d|·U·I_motor). And only a motoring torque
  // (τ along d) draws it: a generating motor — its shaft driven along d faster than ω0, or held
  // by the bridge in its dead zone — turns its current back through the bridge's diodes, the
  // supply gives nothing for that torque (and is credited nothing: the laboratory supply cannot
  // take current back, and the battery's charge acceptance is not modelled).
  const bool motoring = torque_nm * duty > 0.0;
  return no_load_a +
         (motoring ? std::abs(duty) * std::abs(torque_nm) / motor.torque_constant_nm_per_a : 0.0);
}

MotorLine MotorModel::step(double duty, double supply_v, int icr, double shaft_speed_radps,
                           double dt_s) {
  const double steady_radps = steady_no_load_speed_radps(truth_, duty, supply_v, icr);
  // Exact for a command held over dt_s, so the result does not depend on the step size.
  const double decay = std::exp(-dt_s / truth_.lag_time_constant_s);
  no_load_speed_radps_ = steady_radps + (no_load_speed_radps_ - steady_radps) * decay;
  // τ_load·d ≥ 0 of (4.6), the thesis' load torque: the external load pushes the shaft faster
  // than ω0 in the direction of d (the motor's own torque then opposes d: it generates).
  const bool same_sign = (shaft_speed_radps - no_load_speed_radps_) * duty >= 0.0;
  return {no_load_speed_radps_, droop_radps_per_nm(truth_, duty, icr, same_sign),
          stall_torque_nm(truth_, duty, supply_v, icr),
          brake_torque_nm(truth_, supply_v, icr)};
}

}  // namespace marsokhod::sim
