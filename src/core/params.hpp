// Configuration of the rover: const after loading and validation. Every field carries its unit in
// its name and its symbol or source in the thesis ("Mobility and Autonomous Reconfiguration of
// Marsokhod", 2008) in a comment. Its TOML key, type, range, source and meaning are one row of
// the parameter schema (src/config/param_schema.cpp), which drives the loader and generates
// docs/parameters.md. The defaults here are the thesis' values so that pure code and its tests
// can build Params without a file; config/marsokhod.toml is still the one file operators edit,
// every key is required, and a test holds its values equal to these defaults.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace marsokhod {

// Motor indices in the layout (3.1):  [ BL,4  CL,2  FL,0 ] [ AB,7  AF,6 ] [ BR,5  CR,3  FR,1 ]
inline constexpr std::size_t kMotorCount = 8;
inline constexpr std::size_t kWheelCount = 6;
inline constexpr std::size_t kSensorNode = 8;  // µ8
enum MotorIndex : std::size_t {
  kFrontLeft = 0,
  kFrontRight = 1,
  kCenterLeft = 2,
  kCenterRight = 3,
  kBackLeft = 4,
  kBackRight = 5,
  kFrontJoint = 6,  // AF, p6 = -γf
  kRearJoint = 7,   // AB/AR, p7 = +γr
};
inline constexpr std::array<const char*, kMotorCount> kMotorNames = {"FL", "FR", "CL", "CR",
                                                                     "BL", "BR", "AF", "AR"};

using MotorVector = std::array<double, kMotorCount>;

// Chapter 3.1 table and Figure 3.3.
struct GeometryParams {
  double joint_to_exterior_axle_m = 0.145;  // a
  double center_axle_to_joint_m = 0.413;    // b
  double wheel_radius_m = 0.125;            // r: 0.125 with blades on solid ground, 0.115 on granules
  double track_width_m = 0.70;              // Quote 2.1 (fixed width 70 cm)
  double blade_inclination_rad = 0.240;     // i
};

// Chapter 3.2: one communication cycle and the controller registers the driver configures.
struct CycleParams {
  double period_s = 0.0156;  // h (64 Hz); must stay below T(con) = (con+1)·65536/2 MHz
  int con = 0;               // clock / velocity-estimation period register, 0..255
  int icr = 511;             // PWM period register, 255..2047 (15.625 kHz at 511)
};

// Chapter 3.2 and 4.1–4.2.
struct MotorParams {
  int encoder_pulses_per_rev = 115000;      // enc conversion 2π/115000
  double max_no_load_speed_radps = 2.827;   // w, Maxon RE 36 at 24 V
  double nominal_supply_v = 24.0;           // Ū of (4.3), the calibration voltage
  // ζ_i, Procedure 4.5; ζ2 and ζ5 were lost with the table: the mean of the four known wheels.
  MotorVector scale{0.9896, 0.9808, 0.9707, 0.941, 0.9713, 0.9707, 0.9808, 0.9713};
  MotorVector backlash_rad{0, 0, 0, 0, 0, 0, 0.052, 0.250};            // b, Procedure 4.1
  MotorVector initial_position_rad{0, 0, 0, 0, 0, 0, -1.2121, 1.2121};  // p̄⁰, Remark 3.1
};

// W_icr(d) for d ≥ 0 (Procedure 4.4): strictly increasing, duty from 0 to 1; odd for d < 0.
struct MotorCurveParams {
  int icr = 511;
  std::vector<double> duty;
  std::vector<double> no_load_speed_radps;
};

// δ^j of (4.4) for one (h, con) pair (Procedure 4.8); delta[j] multiplies ŵ^(k−j).
struct ResponseParams {
  double period_s = 0.0157;
  int con = 0;
  std::vector<double> delta;
};

enum class SupplyKind { kBattery, kTether };  // the batteries, or the laboratory supply's tether

// The supply's current (Field Experiment 1.1, core/behaviour/supply_current.hpp): on the tether
// the driver keeps the current the duty cycles could draw, every motor stalled, within the
// laboratory supply's limit. The motor's
// constants are a Maxon RE 36 with gearhead GP 42 C behind an L9904 bridge, seen at the output
// shaft; the stationary rover's current is chapter 3.1's table.
struct SupplyCurrentParams {
  double base_current_a = 1.05;              // chapter 3.1: computer, bridges, controllers
  double tether_current_limit_a = 6.0;       // the PS 613's current limit (Figure 4.2)
  // The most µ8's reading of U may lie below the true supply: the divider's and the ADC
  // reference's ±1.5 % over the conversion's span (U − offset ≈ 65 V at 24 V) and 3 counts of
  // offset, 1.2 V before Procedure 3.5 (after it, about 0.1 V). The bound is worked out at U + this.
  double supply_reading_error_v = 1.2;
  double motor_no_load_current_a = 0.12;     // a bridge switching, the motor free
  double motor_current_per_radps_a = 0.06;   // friction losses growing with the shaft's speed
  double motor_torque_constant_nm_per_a = 7.5;   // k_t at the output shaft
  double motor_stall_torque_per_v_nm = 1.74;     // stall torque per volt above the dead zone
  double motor_holding_torque_nm = 5.0;          // the gearhead's and the bridge's hold
  double motor_dead_zone_v = 1.0;                // |d|·U below this does not turn the motor
  // B⁻ of (4.7): a shaft turned against its duty (plugging) gives |w|/B more than its stall torque
  double motor_plugging_droop_radps_per_nm = 0.015;
};

// (4.5) voltage drop and chapter 6.1 power management.
struct PowerParams {
  double duty_drop_v = 0.6;                // ξ [V]
  double load_drop_v_s2_per_rad2 = 0.4;    // Ξ [V s²/rad²]
  double max_drop_v = 1.5;                 // Υ [V]
  double brownout_v = 19.5;                // the onboard computer rebooted here (Field Exp. 6.2)
  SupplyKind supply = SupplyKind::kBattery;  // at start; the operator's configure changes it
  SupplyCurrentParams current;
};

// (4.7): l ≈ τ·B, B⁺ when τd ≥ 0, B⁻ when τd < 0.
struct LoadParams {
  double gain_same_sign_radps_per_nm = 0.030;      // B⁺
  double gain_opposite_sign_radps_per_nm = 0.015;  // B⁻
};

// (4.6) B⁺_icr(d), B⁻_icr(d) for one icr (Procedure 4.13, Figure 4.8): the load per torque at
// duty cycles |d| (strictly increasing in [0, 1]), linear in between, constant beyond the ends,
// even in d (docs/decisions.md).
struct LoadGainParams {
  int icr = 511;
  std::vector<double> duty;
  std::vector<double> same_sign_radps_per_nm;      // B⁺(d), τd ≥ 0
  std::vector<double> opposite_sign_radps_per_nm;  // B⁻(d), τd < 0
};

// (5.3) joint bounds; the contracted bounds are ∓acos(a/b) from the geometry.
struct JointParams {
  double front_min_rad = -2.55;  // p6_min
  double front_max_rad = -1.2121;  // p6_max = -acos(a/b)
  double rear_min_rad = 1.2121;    // p7_min = +acos(a/b)
  double rear_max_rad = 2.55;      // p7_max
  double control_rate_per_s = 0.4;          // μ of (4.15) for the joints (Figure 4.11)
  double control_speed_fraction = 0.5;      // C = fraction·w (Figure 4.11: C = w/2)
  double target_tolerance_rad = 0.05;       // Procedure 4.17
  // How far a unit's joint gap may differ from MotorParams::backlash_rad, as a share of it:
  // the driver keeps that much inside the positive bounds (driver/joint_margin.hpp).
  double backlash_uncertainty = 0.15;
};

// Chapter 5.1: F(c) = slope·c + offset, the exterior-to-center wheel speed ratio when spinning.
struct SpinParams {
  double slope_per_m = 5.3;
  double offset = 0.04;
};

enum class LoadDistributionMode { kOff, kVariance, kSlip };  // off, h^v (6.5), h^s (6.6)

// Chapter 6.3.
struct LoadDistributionParams {
  LoadDistributionMode mode = LoadDistributionMode::kOff;
  double gain_per_radps = 5.0;          // the constant 5 /(rad/s) of (6.5), (6.6)
  double max_correction_radps = 0.3;    // H
};

// Low-pass coefficients "λ close to 1" of chapters 3.3 and 6.2.1 (per cycle).
struct FilterParams {
  double gyro_null_lambda = 0.99;          // null-rate y, (3.4)
  double reference_voltage_lambda = 0.99;  // Ū sequence, Procedure 3.5
  double gravity_lambda = 0.99;            // g, chapter 6.2.1
};

// An affine conversion physical = gain·counts + offset.
struct LinearConversion {
  double gain = 0.0;
  double offset = 0.0;
  double operator()(double counts) const { return gain * counts + offset; }
};

// Procedure 3.3: ADC readings at −g and +g for one accelerometer axis.
struct AccelerometerAxisParams {
  double minus_g_counts = 0.0;
  double plus_g_counts = 0.0;
};

// Chapter 3.3.
struct SensorParams {
  double gravity_mps2 = 9.81;
  double gyro_radps_per_count = 0.0170;       // (3.4)
  double gyro_null_typ_counts = 505.0;        // y TYP (490..520)
  std::array<AccelerometerAxisParams, 3> accelerometer{
      {{145.0, 413.0}, {120.0, 383.0}, {75.0, 376.0}}};  // Procedure 3.3
  LinearConversion tilt_front{0.00495, -2.61};   // θf, Procedure 3.4
  LinearConversion tilt_rear{-0.00526, 2.74};    // θr (SPEC: +2.74)
  LinearConversion supply{0.06768, -41.0823};    // U, Procedure 3.5
};

// Remark 5.7: what full deflection of the gamepad's sticks and buttons asks for.
struct OperatorParams {
  double dead_zone = 0.1;                  // |axis| below this reads as 0 (then rescaled to 0..1)
  double max_drive_speed_radps = 2.25;     // v1ᵈ at full deflection (chapter 5: 0.27 m/s)
  double max_spin_speed_radps = 1.5;       // v2ᵈ at full deflection
  double max_drift_speed_radps = 1.0;      // v3ᵈ while a drift button is held (m3, chapter 5.2)
  double max_trench_speed_radps = 1.0;     // v4ᵈ at full deflection
  double joint_button_speed_radps = 0.5;   // v6ᵈ, v7ᵈ while an extend/contract button is held
  double calibration_duty = 0.08;          // Procedure 4.3: |d6|, |d7| in calibration mode
  double drive_rate_per_s = 2.0;           // μ of (4.14) ramping v1…v4 toward their targets
};

// Chapter 5.3 wheel walking (docs/design.md's gait tables).
struct GaitParams {
  double extended_rad = 2.55;              // E: |p6| = |p7| = 2.55
  double max_joint_speed_fraction = 0.5;   // C of (4.15) at full right stick, as a fraction of w
};

// Chapter 6: each behaviour can be switched off here and at run time.
struct BehaviourParams {
  bool power_management = true;            // (6.3)
  bool slant_response = true;              // 6.2.1
  bool contract_on_turn = true;            // 6.2.2
  bool axle_placement = true;              // 6.2.3
  double slant_deadband_rad = 0.05;        // |σ| below this counts as flat (sensor noise, bumps)
  double axle_placement_load_radps = 0.5;  // |l6|, |l7| above this: the joint is blocked
  double axle_placement_speed_radps = 0.1; // joint slower than this: switch ρ → 1 − ρ at once
  double axle_placement_rate_per_s = 1.0;  // faster: move ρ toward 1 − ρ at this rate
  double axle_placement_hold_s = 0.5;      // the axle ρ moves stopped this long: ρ → 1 − ρ
  // The slope hold (slope_hold.hpp): K·e added to a gait's wheels for the angle e [rad] lost
  // downhill, e ≤ E. K = 0: off.
  double slope_hold_gain_per_s = 10.0;     // K
  double slope_hold_max_rad = 0.1;         // E
  // On a slope the ε-formula's strokes take the joints' mismatch uphill (uphill_axle_factors).
  bool slope_placement = true;
};

// Chapter 3.2's rules for duty cycles, Field Experiment 6.7 and chapter 3.3's dead man's switch.
struct SafetyParams {
  double operator_timeout_s = 0.5;         // no operator input for this long ⇒ controlled stop
  int dead_man_dog = 1;                    // µ8 stops the motors 0.2621·dog s after the last 0x80
  double max_duty_step = 0.05;             // |d^k − d^(k−1)| per cycle ("must not differ much")
  double direction_change_duty = 0.02;     // drv may toggle only while |d| ≤ this ("pwm ≈ 0")
  int missed_responses_limit = 3;          // consecutive missing responses ⇒ fault, rover stopped
  // A restarted driver continues from the joint state its predecessor kept only if it is at
  // most this old (driver/joint_memory.hpp): a brown-out's reboot takes about 30 s.
  double joint_memory_max_age_s = 300.0;
  // The failsafes that need an estimate (core/estimation/failsafes.hpp): roll or pitch of the
  // mean gravity beyond its limit ⇒ "tip-over" fault; the wheels stalled under a command ⇒
  // "stuck" fault after stuck_time_s (0: off).
  double tip_over_roll_rad = 0.6981;         // 40°; the rover rolls over at about 60°
  double tip_over_pitch_rad = 0.6981;        // 40°
  double tip_over_time_constant_s = 0.25;    // the accelerometer's mean
  double stuck_time_s = 5.0;
  double stuck_min_command_radps = 0.2;      // the centre wheels' mean |ν| that counts as driving
  double stuck_turning_share = 0.2;          // stalled: Σ|w| ≤ this · Σ|ν| of the centre wheels
  double stuck_min_yaw_rate_radps = 0.1;     // a rover turning faster is not stuck
  // A joint stalled under a command ⇒ "front joint blocked" / "rear joint blocked" fault after
  // joint_blocked_time_s (0: off).
  double joint_blocked_time_s = 5.0;
  double joint_blocked_min_command_radps = 0.2;  // the joint's |ν| that counts as driving it
  double joint_blocked_turning_share = 0.2;      // stalled: |w| ≤ this · |ν|
};

// Missions for application software (core/navigation/mission.hpp): how the driver turns,
// moves and goes to waypoints by dead reckoning.
struct NavigationParams {
  double cruise_speed_mps = 0.15;          // v1_cruise·r: a move's speed between its ramps
  double min_speed_mps = 0.03;             // v1_min·r: the slowest a leg creeps to its end
  double max_spin_radps = 1.0;             // v2_max: m2's centre-wheel speed turning on the spot
  double min_spin_radps = 0.3;             // v2_min
  double heading_gain = 3.0;               // k_ψ: v2 [rad/s] per radian of heading error
  double look_ahead_m = 0.5;               // L: the heading aims back at the line this far ahead
  double heading_tolerance_rad = 0.0087;   // over twice this off a turn is turned again (0.5°)
  double position_tolerance_m = 0.02;      // a leg ends within this along the line
  double turn_in_place_rad = 0.35;         // goto turns on the spot first beyond this (20°)
  double settle_s = 4.5;                   // standing still this long ends a leg
  double still_yaw_rate_radps = 0.03;      // still: |ω| below this, the driver judging standing
  double max_settle_s = 6.0;               // a leg's settling ends after this anyway
  int max_corrections = 2;                 // legs driven again after ending off, per mission
  double no_progress_s = 10.0;             // no progress this long aborts the mission
};

struct Params {
  GeometryParams geometry;
  CycleParams cycle;
  MotorParams motors;
  // One W table per icr. W₅₁₁ is reconstructed (Figures 3.6/4.2 are lost) through the thesis'
  // anchors: W(0.3) = 0.847 (Example 4.6), W⁻¹(2.429) ≈ 0.826, W(1) = w = 2.827.
  std::vector<MotorCurveParams> motor_curves{
      {511,
       {0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0},
       {0.0, 0.19, 0.52, 0.847, 1.18, 1.50, 1.81, 2.10, 2.37, 2.60, 2.827}}};
  // One δ table per (h, con), the table after Procedure 4.8.
  std::vector<ResponseParams> responses{
      {0.0157, 0, {0.0, 0.2452, 0.3742, 0.2798, 0.1008}},
      {0.0313, 1, {0.0, 0.2449, 0.5592, 0.1960}}};
  PowerParams power;
  LoadParams load;
  // One B± table per icr (4.6). Figure 4.8 is lost; its description ("a reduced modulation
  // frequency increases the load resistance at small duty cycles") is read as B rising below
  // d = 0.3 by 0.5·512/(icr+1) of (4.7)'s constants, which hold above (docs/decisions.md).
  std::vector<LoadGainParams> load_gains{
      {255, {0.0, 0.3, 1.0}, {0.060, 0.030, 0.030}, {0.030, 0.015, 0.015}},
      {511, {0.0, 0.3, 1.0}, {0.045, 0.030, 0.030}, {0.0225, 0.015, 0.015}},
      {1023, {0.0, 0.3, 1.0}, {0.0375, 0.030, 0.030}, {0.01875, 0.015, 0.015}},
      {2047, {0.0, 0.3, 1.0}, {0.03375, 0.030, 0.030}, {0.016875, 0.015, 0.015}}};
  JointParams joints;
  SpinParams spin;
  LoadDistributionParams load_distribution;
  FilterParams filters;
  SensorParams sensors;
  OperatorParams operator_input;
  GaitParams gaits;
  BehaviourParams behaviours;
  SafetyParams safety;
  NavigationParams navigation;
};

}  // namespace marsokhod
