// The simulated rover's true physical parameters: what the driver's calibration (Procedures 3.3,
// 4.4, 4.5, 4.8, 4.13) tries to find. They are close to, never taken from, the driver's nominal
// Params: the W curve is a smooth physical function instead of the table, ζ, the droop, the ±g
// table and the gyro's null rate scatter per unit around the nominal values, drawn once from the
// run's seed. exact_sim_truth() keeps the per-unit values at the nominal ones (for tests that need
// the inverse of the driver's conversions); make_sim_truth() draws them.
//
// Units are in the names; register values (icr, counts) are raw like the firmware's.
#pragma once

#include <array>
#include <cstdint>

#include "core/params.hpp"

namespace marsokhod::sim {

// One Maxon RE 36 with gearhead GP 42 C behind an L9904 H-bridge, seen at the output shaft.
// No-load speed (motor_model.hpp):
//   x = |d|·U − U_dz(icr)  (effective armature voltage above the dead zone, ≥ 0)
//   ω0 = sign(d)·ζ·k(icr)·x / (1 + k(icr)·x/ω_sat)
// The defaults put ω0(0.3, 24 V) = 0.860 and ω0(1, 24 V) = 2.800 rad/s at icr = 511 and ζ = 1
// (the nominal table says 0.847 and 2.827).
struct MotorTruth {
  double scale = 1.0;                           // true ζ_i (Procedure 4.5 measures it)
  double speed_per_volt_radps_per_v = 0.14623;  // k at icr = 511
  double saturation_speed_radps = 16.72;  // ω_sat: friction and ripple losses flatten the top
  double dead_zone_v = 1.0;               // U_dz at icr = 511: static friction, bridge dead time
  // Remark 3.2 / Figure 3.6: a higher icr (lower PWM frequency) overcomes friction at smaller
  // duty cycles and draws more current. U_dz(icr) = U_dz·(512/(icr+1))^exponent,
  // k(icr) = k·(1 + gain·log2((icr+1)/512)).
  double dead_zone_icr_exponent = 0.5;
  double speed_gain_per_icr_octave = 0.02;
  // The delay of the no-load speed behind the steady value of (d, U): first order. With µi's
  // velocity window (ControllerTruth) 12 ms reproduces the δ table after Procedure 4.8:
  // the least-squares δ of the simulated chain is (0, 0.20, 0.40, 0.29, 0.10) at h = 15.7 ms,
  // con = 0 (thesis: 0, 0.245, 0.374, 0.280, 0.101).
  double lag_time_constant_s = 0.012;
  // (4.6)/(4.7): speed lost per N·m of load, B⁺ when the load drives the motor along d
  // (τ·d ≥ 0, the bridge freewheels), B⁻ when it brakes (τ·d < 0). Figure 4.8: at high PWM
  // frequency B grows at small duty; (4.7)'s constants are the low-frequency limit:
  //   B(d, icr) = B·(1 + gain·(512/(icr+1))·max(0, 1 − |d|/low_duty))
  double droop_same_sign_radps_per_nm = 0.030;
  double droop_opposite_sign_radps_per_nm = 0.015;
  double droop_low_duty_gain = 0.5;
  double droop_low_duty = 0.3;
  // The most torque the motor delivers: proportional to x, at least the holding torque of the
  // gearhead and the shorted bridge when x = 0.
  double stall_torque_per_volt_nm_per_v = 1.74;  // 40 N·m at d = 1, 24 V
  double holding_torque_nm = 5.0;
  // Supply current of one bridge: I = I0(icr) + I1·|ω| + |d|·|τ|/k_t while d ≠ 0, the last term
  // only while the motor drives (τ·d > 0), 0 with the bridge off (motor_model.hpp).
  double torque_constant_nm_per_a = 7.5;  // k_t at the output shaft (incl. gearhead losses)
  double no_load_current_a = 0.12;        // I0 at icr = 511
  double no_load_current_a_per_radps = 0.06;
  double current_gain_per_icr_octave = 0.15;  // Remark 3.2: higher icr, more current
  // Joints (6, 7): the true play between shaft and joint, Procedure 4.1 (the physics' gap);
  // wheels 0.
  double backlash_rad = 0.0;
};

enum class SupplyKind : std::uint8_t { kBattery, kTether };

// Two 12 V lead-acid blocks in series (2 × HYS1250, 5 Ah; HYS1240 is 4 Ah):
//   OCV(s) = blocks·(empty_block_v + block_v_per_charge·s)      s = state of charge 0..1
//   R(s)   = r_full + r_empty_extra·(1 − s)²                    (grows as the acid thins)
//   U = OCV − I·R − V_p,  τ_p·dV_p/dt = I·R_p − V_p             (polarisation: sag, then recovery)
struct BatteryTruth {
  double capacity_ah = 5.0;
  double initial_state_of_charge = 0.8;
  int blocks = 2;
  double empty_block_v = 11.8;
  double block_v_per_charge = 0.95;  // 12.75 V per block when full
  double resistance_full_ohm = 0.15;
  double resistance_empty_extra_ohm = 0.15;
  double polarisation_resistance_ohm = 0.06;
  double polarisation_time_constant_s = 5.0;
};

// The 0–30 V laboratory supply on a tether (Figure 4.2's PS 613): constant voltage behind the
// cable's resistance until the current limit, above it a steep foldback of the voltage.
struct TetherTruth {
  double set_v = 24.0;
  double current_limit_a = 6.0;
  double cable_resistance_ohm = 0.1;
  double foldback_ohm_per_a = 4.0;  // volts lost per ampere above the limit
};

// Chapter 3.1's table of the stationary rover at 24 V, and the onboard computer's brown-out.
struct PowerTruth {
  SupplyKind supply = SupplyKind::kBattery;
  BatteryTruth battery;
  TetherTruth tether;
  double computer_load_a = 0.69;    // converter 10 A, ReadyBoard, PC104 modules
  double bridge_load_a = 0.13;      // H-bridges, CAN interface
  double controller_load_a = 0.23;  // converter 5 A, controllers, encoders, analog sensors
  double brownout_v = 19.5;         // the onboard computer rebooted here (Field Experiment 6.2)
  double reboot_s = 30.0;           // how long it stays off after a brown-out
};

// µ8's analog side: the true conversions the driver's chapter 3.3 constants approximate.
struct SensorTruth {
  double gravity_mps2 = 9.81;
  // Gyro null rate: base + amplitude·sin(2πt/period + phase), within a 5 LSB window and at most
  // amplitude·2π/period ≤ 0.01 LSB/s (chapter 3.3).
  double gyro_null_base_counts = 505.0;
  double gyro_drift_amplitude_counts = 2.0;
  double gyro_drift_period_s = 2000.0;
  double gyro_drift_phase_rad = 0.0;
  double gyro_radps_per_count = 0.0170;
  std::array<AccelerometerAxisParams, 3> accelerometer{
      {{145.0, 413.0}, {120.0, 383.0}, {75.0, 376.0}}};  // true ±g readings, Procedure 3.3
  LinearConversion tilt_front{0.00495, -2.61};
  LinearConversion tilt_rear{-0.00526, 2.74};
  double tilt_backlash_rad = 0.13962634;  // 8° of play on the potentiometer shafts
  LinearConversion supply{0.06768, -41.0823};
  // Gaussian noise before quantisation [counts].
  double gyro_noise_counts = 0.4;
  double accelerometer_noise_counts = 0.7;
  double tilt_noise_counts = 0.3;
  double supply_noise_counts = 0.3;
};

// The controllers' timing.
struct ControllerTruth {
  double response_latency_s = 50e-6;  // request received → response ready to send
  // vel's moving window over T(con) in slices of T(con)/S (motor_controller.hpp); S = 1 counts
  // between the last two overflows of tim.
  int velocity_window_slices = 16;
};

struct SimTruth {
  std::uint64_t seed = 0;
  std::array<MotorTruth, kMotorCount> motors{};
  PowerTruth power;
  SensorTruth sensors;
  ControllerTruth controllers;
};

// The nominal unit: ζ_i = params' ζ_i, the ±g table, tilt and supply conversions and the gyro
// base line as configured, one lag (12 ms) for every motor; noise kept. The W curve and the droop
// are still the simulator's own.
SimTruth exact_sim_truth(const Params& params);

// A unit drawn from seed: ζ_i within ±2 % of the nominal, lag 10–14 ms, droop ±5 %, dead zone
// ±10 %, the joints' backlash 6–15 % above or below the nominal, ±g readings ±2 counts, gyro
// base line 505 ± 5 and its drift's amplitude/period/phase, tilt offsets within 3 counts, the
// supply's offset within 3 counts and its gain ±1.5 %. Deterministic: equal seeds give equal
// truths.
SimTruth make_sim_truth(const Params& params, std::uint64_t seed);

}  // namespace marsokhod::sim
