// One motor of the simulated rover: duty cycle, PWM period and supply voltage in; the speed–torque
// line the physics drives the shaft with, and the current the bridge draws, out.
//
// The physics (sim/physics/rover_physics.hpp) delivers τ = clamp((ω0 − ω)/B, ±τ_stall) at the
// output shaft. This model supplies ω0, B and τ_stall from MotorTruth:
//   x(d, U, icr) = max(0, |d|·U − U_dz(icr))
//   ω_ss = sign(d)·ζ·k(icr)·x/(1 + k(icr)·x/ω_sat)            steady no-load speed (cf. (4.3))
//   ω0 ← ω_ss + (ω0 − ω_ss)·exp(−dt/τ_lag)                   response lag (what δ of (4.4) sees)
//   B = B⁺ if (ω − ω0)·d ≥ 0 (load drives along d), B⁻ otherwise   (4.6)/(4.7), the sign of
//                                    τ_load·d with the thesis' load torque τ_load
//   τ_stall = max(τ_hold, c_stall·x)
//   I = I0(icr) + I1·|ω| + |d|·|τ|/k_t   while d ≠ 0 and τ·d > 0, τ = (ω0 − ω)/B the motor's own
//                                    torque (= −τ_load) (motoring; the supply feeds the
//                                    motor's current only while the bridge conducts, |d| of
//                                    each PWM period)
//   I = I0(icr) + I1·|ω|             while τ·d ≤ 0 (generating: the current returns through the
//                                    bridge's diodes, the supply gives nothing for the torque)
//   I = 0                            with the bridge off
// Unlike the driver's (4.3), ω_ss is not proportional to U (the dead zone and the saturation are
// not), so the driver's U/Ū normalisation is close but not exact, as on the real rover.
#pragma once

#include "core/params.hpp"
#include "sim/electrics/sim_truth.hpp"

namespace marsokhod::sim {

inline constexpr int kReferenceIcr = 511;  // the icr at which MotorTruth's values hold

// The speed–torque line of one motor for the next physics steps.
struct MotorLine {
  double no_load_speed_radps = 0.0;  // ω0, after the lag
  double droop_radps_per_nm = 0.0;   // B
  double stall_torque_nm = 0.0;      // τ_stall: the most it delivers along d (motoring)
  double brake_torque_nm = 0.0;      // the most it resists a load driving it (generating)
};

// The same for all eight motors; field for field the physics' MotorDrive.
struct MotorDriveCommand {
  MotorVector no_load_speed_radps{};
  MotorVector droop_radps_per_nm{};
  MotorVector stall_torque_nm{};
  MotorVector brake_torque_nm{};
};

// Effective armature voltage above the dead zone, x(d, U, icr) [V], ≥ 0.
double effective_voltage_v(const MotorTruth& motor, double duty, double supply_v, int icr);

// ω_ss: the no-load speed the motor settles at [rad/s], odd in d.
double steady_no_load_speed_radps(const MotorTruth& motor, double duty, double supply_v, int icr);

// B⁺ or B⁻ at (d, icr) [rad/s per N·m]; same_sign: the load drives the shaft along d.
double droop_radps_per_nm(const MotorTruth& motor, double duty, int icr, bool same_sign);

// τ_stall [N·m].
double stall_torque_nm(const MotorTruth& motor, double duty, double supply_v, int icr);

// The most a motor resists a load that drives it [N·m]: a shaft driven past its no-load speed
// raises a back-EMF above the bridge's average voltage (it generates), one driven against its
// duty adds its back-EMF to it (it plugs), and the current grows with the speed, not limited by
// the duty. It is bounded here at the full-duty stall torque (the armature current U/R, the most
// the bridge and the winding carry), whatever the duty; the physics lets a wheel's bound grow
// from τ_stall toward it with the speed (rover_physics.hpp).
double brake_torque_nm(const MotorTruth& motor, double supply_v, int icr);

// Supply current of the motor's bridge [A].
double motor_current_a(const MotorTruth& motor, double duty, int icr, double torque_nm,
                       double shaft_speed_radps);

class MotorModel {
 public:
  explicit MotorModel(const MotorTruth& truth) : truth_(truth) {}

  // Advances the lag by dt_s toward ω_ss(duty, supply_v, icr) and returns the line for the next
  // physics step. shaft_speed_radps (the last measured ω) picks B⁺ or B⁻.
  MotorLine step(double duty, double supply_v, int icr, double shaft_speed_radps, double dt_s);

  double no_load_speed_radps() const { return no_load_speed_radps_; }
  const MotorTruth& truth() const { return truth_; }

 private:
  MotorTruth truth_;
  double no_load_speed_radps_ = 0.0;
};

}  // namespace marsokhod::sim
