// Every parameter of config/marsokhod.toml: its key, field, range, unit, thesis symbol and source,
// and what it means. The loader reads and checks by this table, error messages quote its ranges,
// and docs/parameters.md is generated from it (marsokhod-param-docs). Ranges are what the code can
// work with, not what the thesis measured; the values themselves are in params.hpp and the file.
#include "config/param_schema.hpp"

#include <numbers>

namespace marsokhod::config {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kLambdaMax = 0.999999;  // a low-pass with λ = 1 would never move

constexpr ParamSpec kGeometry[] = {
    {.key = "joint_to_exterior_axle_m", .field = field<&GeometryParams::joint_to_exterior_axle_m>,
     .min = 0.01, .max = 1.0, .unit = "m", .symbol = "a",
     .about = "from a joint to the exterior axle on its lever"},
    {.key = "center_axle_to_joint_m", .field = field<&GeometryParams::center_axle_to_joint_m>,
     .min = 0.01, .max = 2.0, .unit = "m", .symbol = "b",
     .about = "from the center axle to a joint; must exceed a"},
    {.key = "wheel_radius_m", .field = field<&GeometryParams::wheel_radius_m>, .min = 0.05,
     .max = 0.5, .unit = "m", .symbol = "r",
     .about = "wheel radius: 0.125 with the blades on solid ground, 0.115 on granules"},
    {.key = "track_width_m", .field = field<&GeometryParams::track_width_m>, .min = 0.1, .max = 3.0,
     .unit = "m", .source = "Quote 2.1", .about = "track width, fixed at 70 cm"},
    {.key = "blade_inclination_rad", .field = field<&GeometryParams::blade_inclination_rad>,
     .min = 0.0, .max = kPi / 2, .unit = "rad", .symbol = "i",
     .about = "inclination of the blades"},
};

constexpr ParamSpec kCycle[] = {
    {.key = "period_s", .field = field<&CycleParams::period_s>, .min = 0.001, .max = 0.5,
     .unit = "s", .symbol = "h",
     .about = "one communication cycle (64 Hz); must stay below T(con) = (con+1)·65536/2 MHz"},
    {.key = "con", .field = field<&CycleParams::con>, .min = 0, .max = 255, .symbol = "con",
     .about = "clock and velocity-estimation period register of µ0–µ7"},
    {.key = "icr", .field = field<&CycleParams::icr>, .min = 255, .max = 2047, .symbol = "icr",
     .about = "PWM period register: (icr+1)/8 MHz, 15.625 kHz at 511; needs its [[motor_curve]]"},
};

constexpr ParamSpec kMotors[] = {
    {.key = "encoder_pulses_per_rev", .field = field<&MotorParams::encoder_pulses_per_rev>,
     .min = 1, .max = 100'000'000, .source = "chapter 3.2",
     .about = "encoder counts per turn: enc·2π/115000 rad"},
    {.key = "max_no_load_speed_radps", .field = field<&MotorParams::max_no_load_speed_radps>,
     .min = 0.1, .max = 100.0, .unit = "rad/s", .symbol = "w",
     .about = "no-load speed at full duty (Maxon RE 36 at 24 V)"},
    {.key = "nominal_supply_v", .field = field<&MotorParams::nominal_supply_v>, .min = 1.0,
     .max = 100.0, .unit = "V", .symbol = "Ū", .source = "(4.3)",
     .about = "the calibration voltage"},
    {.key = "scale", .field = field<&MotorParams::scale>, .min = 0.5, .max = 1.5, .symbol = "ζ_i",
     .source = "Procedure 4.5",
     .about = "per motor 0…7 (FL FR CL CR BL BR AF AR): speed relative to W; ζ2, ζ5 were lost and "
              "are the mean of the four printed wheels",
     .calibrated = true},
    {.key = "backlash_rad", .field = field<&MotorParams::backlash_rad>, .min = 0.0, .max = 1.0,
     .unit = "rad", .symbol = "b", .source = "Procedure 4.1",
     .about = "per motor: the gear's gap; front joint ≈ 3°, rear ≈ 14°, wheels neglected",
     .calibrated = true},
    {.key = "initial_position_rad", .field = field<&MotorParams::initial_position_rad>,
     .min = -10.0, .max = 10.0, .unit = "rad", .symbol = "p̄⁰", .source = "Remark 3.1",
     .about = "per motor: position at start; the joints vertical, ∓acos(a/b)"},
};

constexpr ParamSpec kMotorCurve[] = {
    {.key = "icr", .field = field<&MotorCurveParams::icr>, .min = 255, .max = 2047, .symbol = "icr",
     .about = "the PWM period register this table holds for", .calibrated = true},
    {.key = "duty", .field = field<&MotorCurveParams::duty>, .min = 0.0, .max = 1.0, .min_count = 2,
     .max_count = 256, .symbol = "d",
     .about = "duty cycles from 0 to 1, strictly increasing", .calibrated = true},
    {.key = "no_load_speed_radps", .field = field<&MotorCurveParams::no_load_speed_radps>,
     .min = 0.0, .max = 100.0, .min_count = 2, .max_count = 256, .unit = "rad/s", .symbol = "W(d)",
     .about = "no-load speed at U = Ū for each duty, from 0, strictly increasing",
     .calibrated = true},
};

constexpr ParamSpec kResponse[] = {
    {.key = "period_s", .field = field<&ResponseParams::period_s>, .min = 0.001, .max = 0.5,
     .unit = "s", .symbol = "h", .about = "the cycle period this table holds for (±1 ms)",
     .calibrated = true},
    {.key = "con", .field = field<&ResponseParams::con>, .min = 0, .max = 255, .symbol = "con",
     .about = "the clock register this table holds for", .calibrated = true},
    {.key = "delta", .field = field<&ResponseParams::delta>, .min = -2.0, .max = 2.0,
     .min_count = 1, .max_count = 256, .symbol = "δ^j", .about = "delta[j] multiplies ŵ^(k−j)",
     .calibrated = true},
};

constexpr std::string_view kSupplyKinds[] = {"battery", "tether"};

constexpr ParamSpec kPower[] = {
    {.key = "duty_drop_v", .field = field<&PowerParams::duty_drop_v>, .min = 0.0, .max = 10.0,
     .unit = "V", .symbol = "ξ", .source = "(4.5)",
     .about = "voltage drop per unit of duty (2 × HYS1240 or 2 × HYS1250)", .calibrated = true},
    {.key = "load_drop_v_s2_per_rad2", .field = field<&PowerParams::load_drop_v_s2_per_rad2>,
     .min = 0.0, .max = 10.0, .unit = "V s²/rad²", .symbol = "Ξ", .source = "(4.5)",
     .about = "voltage drop per squared load", .calibrated = true},
    {.key = "max_drop_v", .field = field<&PowerParams::max_drop_v>, .min = 0.01, .max = 10.0,
     .unit = "V", .symbol = "Υ", .source = "(6.3)",
     .about = "power management keeps Ū − U below this"},
    {.key = "brownout_v", .field = field<&PowerParams::brownout_v>, .min = 0.0, .max = 100.0,
     .unit = "V", .source = "Field Experiment 6.2", .about = "the onboard computer rebooted here"},
    {.key = "supply", .field = field<&PowerParams::supply>, .choices = kSupplyKinds,
     .source = "Field Experiment 1.1",
     .about = "battery, or tether: the supply's current is kept within tether_current_limit_a"},
    {.key = "base_current_a", .field = field<&PowerParams::current, &SupplyCurrentParams::base_current_a>,
     .min = 0.0, .max = 10.0, .unit = "A", .source = "chapter 3.1",
     .about = "the stationary rover's current (computer, bridges, controllers)"},
    {.key = "tether_current_limit_a",
     .field = field<&PowerParams::current, &SupplyCurrentParams::tether_current_limit_a>, .min = 0.5,
     .max = 30.0, .unit = "A", .source = "Field Experiment 1.1",
     .about = "the laboratory supply's current limit (PS 613: 6 A)"},
    {.key = "supply_reading_error_v",
     .field = field<&PowerParams::current, &SupplyCurrentParams::supply_reading_error_v>,
     .min = 0.0, .max = 5.0, .unit = "V", .source = "Procedure 3.5",
     .about = "the most µ8's reading of U may lie below the supply (the current bound takes U + "
              "this): 1.2 V before Procedure 3.5, about 0.1 V after",
     .calibrated = true},
    {.key = "motor_no_load_current_a",
     .field = field<&PowerParams::current, &SupplyCurrentParams::motor_no_load_current_a>,
     .min = 0.0, .max = 5.0, .unit = "A", .about = "a motor's bridge switching, the shaft free"},
    {.key = "motor_current_per_radps_a",
     .field = field<&PowerParams::current, &SupplyCurrentParams::motor_current_per_radps_a>,
     .min = 0.0, .max = 5.0, .unit = "A s/rad", .about = "a motor's losses growing with its speed"},
    {.key = "motor_torque_constant_nm_per_a",
     .field = field<&PowerParams::current, &SupplyCurrentParams::motor_torque_constant_nm_per_a>,
     .min = 0.1, .max = 100.0, .unit = "N m/A", .symbol = "k_t",
     .about = "torque per ampere at the output shaft"},
    {.key = "motor_stall_torque_per_v_nm",
     .field = field<&PowerParams::current, &SupplyCurrentParams::motor_stall_torque_per_v_nm>,
     .min = 0.0, .max = 100.0, .unit = "N m/V",
     .about = "the most torque per volt of |d|·U above the dead zone"},
    {.key = "motor_holding_torque_nm",
     .field = field<&PowerParams::current, &SupplyCurrentParams::motor_holding_torque_nm>,
     .min = 0.0, .max = 100.0, .unit = "N m", .about = "the torque a motor holds in its dead zone"},
    {.key = "motor_dead_zone_v",
     .field = field<&PowerParams::current, &SupplyCurrentParams::motor_dead_zone_v>, .min = 0.0,
     .max = 24.0, .unit = "V", .about = "|d|·U below this does not turn the motor"},
    {.key = "motor_plugging_droop_radps_per_nm",
     .field = field<&PowerParams::current, &SupplyCurrentParams::motor_plugging_droop_radps_per_nm>,
     .min = 0.001, .max = 1.0, .unit = "rad/(s N m)", .symbol = "B⁻", .source = "(4.7)",
     .about = "a shaft turned against its duty gives |w|/B more torque than its stall torque"},
};

constexpr ParamSpec kLoad[] = {
    {.key = "gain_same_sign_radps_per_nm", .field = field<&LoadParams::gain_same_sign_radps_per_nm>,
     .min = 1e-6, .max = 10.0, .unit = "rad/(s N m)", .symbol = "B⁺",
     .about = "l ≈ τ·B⁺ when τd ≥ 0", .calibrated = true},
    {.key = "gain_opposite_sign_radps_per_nm",
     .field = field<&LoadParams::gain_opposite_sign_radps_per_nm>, .min = 1e-6, .max = 10.0,
     .unit = "rad/(s N m)", .symbol = "B⁻", .about = "l ≈ τ·B⁻ when τd < 0", .calibrated = true},
};

constexpr ParamSpec kLoadGain[] = {
    {.key = "icr", .field = field<&LoadGainParams::icr>, .min = 255, .max = 2047, .symbol = "icr",
     .about = "the PWM period register this table holds for", .calibrated = true},
    {.key = "duty", .field = field<&LoadGainParams::duty>, .min = 0.0, .max = 1.0, .min_count = 1,
     .max_count = 64, .symbol = "|d|",
     .about = "duty cycles, strictly increasing; B± is linear in between, constant beyond, even "
              "in d",
     .calibrated = true},
    {.key = "same_sign_radps_per_nm", .field = field<&LoadGainParams::same_sign_radps_per_nm>,
     .min = 1e-6, .max = 10.0, .min_count = 1, .max_count = 64, .unit = "rad/(s N m)",
     .symbol = "B⁺(d)", .about = "l = τ·B⁺(d) when τd ≥ 0, one per duty", .calibrated = true},
    {.key = "opposite_sign_radps_per_nm",
     .field = field<&LoadGainParams::opposite_sign_radps_per_nm>, .min = 1e-6, .max = 10.0,
     .min_count = 1, .max_count = 64, .unit = "rad/(s N m)", .symbol = "B⁻(d)",
     .about = "l = τ·B⁻(d) when τd < 0, one per duty", .calibrated = true},
};

constexpr ParamSpec kJoints[] = {
    {.key = "front_min_rad", .field = field<&JointParams::front_min_rad>, .min = -kPi, .max = 0.0,
     .unit = "rad", .symbol = "p6_min", .about = "front joint fully extended"},
    {.key = "front_max_rad", .field = field<&JointParams::front_max_rad>, .min = -kPi, .max = 0.0,
     .unit = "rad", .symbol = "p6_max", .about = "front joint vertical, −acos(a/b)"},
    {.key = "rear_min_rad", .field = field<&JointParams::rear_min_rad>, .min = 0.0, .max = kPi,
     .unit = "rad", .symbol = "p7_min", .about = "rear joint vertical, +acos(a/b)"},
    {.key = "rear_max_rad", .field = field<&JointParams::rear_max_rad>, .min = 0.0, .max = kPi,
     .unit = "rad", .symbol = "p7_max", .about = "rear joint fully extended"},
    {.key = "control_rate_per_s", .field = field<&JointParams::control_rate_per_s>, .min = 0.001,
     .max = 100.0, .unit = "1/s", .symbol = "μ", .source = "(4.15), Figure 4.11",
     .about = "rate of the joints' position control"},
    {.key = "control_speed_fraction", .field = field<&JointParams::control_speed_fraction>,
     .min = 0.01, .max = 1.0, .symbol = "C/w", .source = "(4.15), Figure 4.11",
     .about = "the joints' speed bound C as a fraction of w (C = w/2)"},
    {.key = "target_tolerance_rad", .field = field<&JointParams::target_tolerance_rad>,
     .min = 0.001, .max = 1.0, .unit = "rad", .source = "Procedure 4.17",
     .about = "a joint target counts as reached within this"},
    {.key = "backlash_uncertainty", .field = field<&JointParams::backlash_uncertainty>, .min = 0.0,
     .max = 0.5, .source = "docs/decisions.md",
     .about = "share by which a unit's joint gap may differ from motors.backlash_rad (drawn "
              "units: 6–15 %); the driver keeps p6, p7 that share of the gap inside their "
              "positive bounds"},
};

constexpr ParamSpec kSpin[] = {
    {.key = "slope_per_m", .field = field<&SpinParams::slope_per_m>, .min = 0.0, .max = 100.0,
     .unit = "1/m", .about = "F(c) = slope·c + offset: exterior-to-center wheel speed ratio",
     .calibrated = true},
    {.key = "offset", .field = field<&SpinParams::offset>, .min = -10.0, .max = 10.0,
     .about = "the offset of F(c)", .calibrated = true},
};

constexpr std::string_view kLoadDistributionModes[] = {"off", "v", "s"};

constexpr ParamSpec kLoadDistribution[] = {
    {.key = "mode", .field = field<&LoadDistributionParams::mode>,
     .choices = kLoadDistributionModes,
     .source = "(6.5), (6.6)", .about = "off, h^v (6.5) or h^s (6.6)"},
    {.key = "gain_per_radps", .field = field<&LoadDistributionParams::gain_per_radps>, .min = 0.0,
     .max = 100.0, .unit = "s/rad", .source = "(6.5), (6.6)", .about = "the constant 5 /(rad/s)"},
    {.key = "max_correction_radps", .field = field<&LoadDistributionParams::max_correction_radps>,
     .min = 0.0, .max = 3.0, .unit = "rad/s", .symbol = "H", .about = "largest correction"},
};

constexpr ParamSpec kFilters[] = {
    {.key = "gyro_null_lambda", .field = field<&FilterParams::gyro_null_lambda>, .min = 0.0,
     .max = kLambdaMax, .symbol = "λ", .source = "(3.4)", .about = "null-rate reading y"},
    {.key = "reference_voltage_lambda", .field = field<&FilterParams::reference_voltage_lambda>,
     .min = 0.0, .max = kLambdaMax, .symbol = "λ", .source = "Procedure 3.5",
     .about = "reference voltage Ū"},
    {.key = "gravity_lambda", .field = field<&FilterParams::gravity_lambda>, .min = 0.0,
     .max = kLambdaMax, .symbol = "λ", .source = "chapter 6.2.1",
     .about = "gravity direction g (1.6 s: not fooled by the accelerations of driving)"},
};

constexpr ParamSpec kSensors[] = {
    {.key = "gravity_mps2", .field = field<&SensorParams::gravity_mps2>, .min = 1.0, .max = 30.0,
     .unit = "m/s²", .symbol = "g", .about = "gravity"},
    {.key = "gyro_radps_per_count", .field = field<&SensorParams::gyro_radps_per_count>,
     .min = 1e-6, .max = 1.0, .unit = "rad/s", .source = "(3.4)",
     .about = "gyro rate per count, at room temperature"},
    {.key = "gyro_null_typ_counts", .field = field<&SensorParams::gyro_null_typ_counts>, .min = 0.0,
     .max = 1023.0, .symbol = "y", .source = "(3.4)", .about = "gyro base line (490..520)"},
    {.key = "accelerometer_minus_g_counts",
     .field = column<&SensorParams::accelerometer, &AccelerometerAxisParams::minus_g_counts>,
     .min = 0.0, .max = 1023.0, .source = "Procedure 3.3, (3.5)",
     .about = "ADC reading of x1, x2, x3 with the axis along −g", .calibrated = true},
    {.key = "accelerometer_plus_g_counts",
     .field = column<&SensorParams::accelerometer, &AccelerometerAxisParams::plus_g_counts>,
     .min = 0.0, .max = 1023.0, .source = "Procedure 3.3, (3.5)",
     .about = "ADC reading of x1, x2, x3 with the axis along +g", .calibrated = true},
    {.key = "tilt_front_rad_per_count",
     .field = field<&SensorParams::tilt_front, &LinearConversion::gain>, .min = -1.0, .max = 1.0,
     .unit = "rad", .symbol = "θf", .source = "Procedure 3.4", .about = "θf = 0.00495·tltᶠ − 2.61",
     .calibrated = true},
    {.key = "tilt_front_offset_rad",
     .field = field<&SensorParams::tilt_front, &LinearConversion::offset>, .min = -10.0,
     .max = 10.0, .unit = "rad", .symbol = "θf", .source = "Procedure 3.4", .about = "its offset",
     .calibrated = true},
    {.key = "tilt_rear_rad_per_count",
     .field = field<&SensorParams::tilt_rear, &LinearConversion::gain>, .min = -1.0, .max = 1.0,
     .unit = "rad", .symbol = "θr", .source = "Procedure 3.4",
     .about = "θr = −0.00526·tltʳ + 2.74 (docs/design.md: +2.74)", .calibrated = true},
    {.key = "tilt_rear_offset_rad",
     .field = field<&SensorParams::tilt_rear, &LinearConversion::offset>, .min = -10.0, .max = 10.0,
     .unit = "rad", .symbol = "θr", .source = "Procedure 3.4", .about = "its offset",
     .calibrated = true},
    {.key = "supply_v_per_count", .field = field<&SensorParams::supply, &LinearConversion::gain>,
     .min = 1e-6, .max = 1.0, .unit = "V", .symbol = "U", .source = "Procedure 3.5",
     .about = "U = 0.06768·vcc − 41.0823", .calibrated = true},
    {.key = "supply_offset_v", .field = field<&SensorParams::supply, &LinearConversion::offset>,
     .min = -100.0, .max = 100.0, .unit = "V", .symbol = "U", .source = "Procedure 3.5",
     .about = "its offset", .calibrated = true},
};

constexpr ParamSpec kOperator[] = {
    {.key = "dead_zone", .field = field<&OperatorParams::dead_zone>, .min = 0.0, .max = 0.9,
     .about = "|axis| below this reads as 0; above it is rescaled to 0..1"},
    {.key = "max_drive_speed_radps", .field = field<&OperatorParams::max_drive_speed_radps>,
     .min = 0.0, .max = 100.0, .unit = "rad/s", .symbol = "v1ᵈ",
     .about = "drive speed at full deflection (chapter 5: 0.27 m/s at r = 0.12 m)"},
    {.key = "max_spin_speed_radps", .field = field<&OperatorParams::max_spin_speed_radps>,
     .min = 0.0, .max = 100.0, .unit = "rad/s", .symbol = "v2ᵈ",
     .about = "spin speed at full deflection"},
    {.key = "max_drift_speed_radps", .field = field<&OperatorParams::max_drift_speed_radps>,
     .min = 0.0, .max = 100.0, .unit = "rad/s", .symbol = "v3ᵈ", .source = "chapter 5.2",
     .about = "sideways drift (m3) speed while X or A is held"},
    {.key = "max_trench_speed_radps", .field = field<&OperatorParams::max_trench_speed_radps>,
     .min = 0.0, .max = 100.0, .unit = "rad/s", .symbol = "v4ᵈ",
     .about = "trench speed at full deflection"},
    {.key = "joint_button_speed_radps", .field = field<&OperatorParams::joint_button_speed_radps>,
     .min = 0.0, .max = 100.0, .unit = "rad/s", .symbol = "v6ᵈ, v7ᵈ",
     .about = "joint speed while an extend or contract button is held"},
    {.key = "calibration_duty", .field = field<&OperatorParams::calibration_duty>, .min = 0.0,
     .max = 0.5, .symbol = "|d6|, |d7|", .source = "Procedure 4.3",
     .about = "the joints' duty in calibration mode"},
    {.key = "drive_rate_per_s", .field = field<&OperatorParams::drive_rate_per_s>, .min = 0.01,
     .max = 100.0, .unit = "1/s", .symbol = "μ", .source = "(4.14)",
     .about = "rate that ramps v1…v4 toward their targets"},
};

constexpr ParamSpec kGaits[] = {
    {.key = "extended_rad", .field = field<&GaitParams::extended_rad>, .min = 0.0, .max = kPi,
     .unit = "rad", .symbol = "E", .about = "extended joints: p6 = −E, p7 = +E"},
    {.key = "max_joint_speed_fraction", .field = field<&GaitParams::max_joint_speed_fraction>,
     .min = 0.01, .max = 1.0, .symbol = "C/w", .source = "(4.15)",
     .about = "the joints' speed bound at full right stick, as a fraction of w"},
};

constexpr ParamSpec kBehaviours[] = {
    {.key = "power_management", .field = field<&BehaviourParams::power_management>,
     .source = "(6.3)", .about = "D keeps the voltage drop below Υ"},
    {.key = "slant_response", .field = field<&BehaviourParams::slant_response>,
     .source = "chapter 6.2.1", .about = "extend the downhill joint"},
    {.key = "contract_on_turn", .field = field<&BehaviourParams::contract_on_turn>,
     .source = "chapter 6.2.2", .about = "contract the joints while spinning"},
    {.key = "axle_placement", .field = field<&BehaviourParams::axle_placement>,
     .source = "chapter 6.2.3", .about = "ρ → 1 − ρ when a joint is blocked"},
    {.key = "slant_deadband_rad", .field = field<&BehaviourParams::slant_deadband_rad>, .min = 0.0,
     .max = 0.5, .unit = "rad", .source = "chapter 6.2.1",
     .about = "slopes below this (≈ 3°) count as flat: sensor noise, bumps"},
    {.key = "axle_placement_load_radps",
     .field = field<&BehaviourParams::axle_placement_load_radps>,
     .min = 0.0, .max = 100.0, .unit = "rad/s", .source = "chapter 6.2.3",
     .about = "|l6|, |l7| above this: the joint is blocked"},
    {.key = "axle_placement_speed_radps",
     .field = field<&BehaviourParams::axle_placement_speed_radps>, .min = 0.0, .max = 100.0,
     .unit = "rad/s", .source = "chapter 6.2.3",
     .about = "a joint slower than this switches ρ at once"},
    {.key = "axle_placement_rate_per_s",
     .field = field<&BehaviourParams::axle_placement_rate_per_s>,
     .min = 0.0, .max = 1000.0, .unit = "1/s", .source = "chapter 6.2.3",
     .about = "a faster one moves ρ gradually at this rate"},
    {.key = "axle_placement_hold_s", .field = field<&BehaviourParams::axle_placement_hold_s>,
     .min = 0.0, .max = 10.0, .unit = "s", .source = "chapter 6.2.3, our extension",
     .about = "the axle ρ moves stopped though driven this long: ρ → 1 − ρ (docs/decisions.md)"},
    {.key = "slope_hold_gain_per_s", .field = field<&BehaviourParams::slope_hold_gain_per_s>,
     .min = 0.0, .max = 100.0, .unit = "1/s", .source = "our extension (slope_hold.hpp)",
     .about = "K: on a slope a gait's wheels get K·e more for the angle e lost downhill; 0: off"},
    {.key = "slope_hold_max_rad", .field = field<&BehaviourParams::slope_hold_max_rad>,
     .min = 0.0, .max = 1.0, .unit = "rad", .source = "our extension (slope_hold.hpp)",
     .about = "E: the lost angle the slope hold counts at most (K·E: the most it asks)"},
    {.key = "slope_placement", .field = field<&BehaviourParams::slope_placement>,
     .source = "our extension (axle_placement.hpp)",
     .about = "on a slope rolking's centre stroke asks no anchor downhill (docs/decisions.md)"},
};

constexpr ParamSpec kSafety[] = {
    {.key = "operator_timeout_s", .field = field<&SafetyParams::operator_timeout_s>, .min = 0.05,
     .max = 1.0, .unit = "s", .source = "Field Experiment 6.7",
     .about = "no operator command for this long ⇒ controlled stop; longer lets a rover whose link "
              "dropped drive on too long"},
    {.key = "dead_man_dog", .field = field<&SafetyParams::dead_man_dog>, .min = 0, .max = 255,
     .symbol = "dog", .source = "chapter 3.3",
     .about = "µ8 stops the motors 0.2621·dog s after the last 0x80 (0.26 s)"},
    {.key = "max_duty_step", .field = field<&SafetyParams::max_duty_step>, .min = 0.001, .max = 2.0,
     .source = "chapter 3.2",
     .about = "|d^k − d^(k−1)| per cycle: consecutive duties differ little"},
    {.key = "direction_change_duty", .field = field<&SafetyParams::direction_change_duty>,
     .min = 0.0, .max = 0.2, .source = "chapter 3.2", .about = "drv toggles only while |d| ≤ this"},
    {.key = "missed_responses_limit", .field = field<&SafetyParams::missed_responses_limit>,
     .min = 1, .max = 1000, .source = "docs/decisions.md",
     .about = "consecutive missing responses of a controller ⇒ fault, stop"},
    {.key = "joint_memory_max_age_s", .field = field<&SafetyParams::joint_memory_max_age_s>,
     .min = 0.0, .max = 86400.0, .source = "docs/decisions.md",
     .about = "a restarted driver continues from a kept joint state at most this old"},
    {.key = "tip_over_roll_rad", .field = field<&SafetyParams::tip_over_roll_rad>, .min = 0.01,
     .max = kPi / 2, .unit = "rad", .source = "docs/decisions.md",
     .about = "the chassis' mean roll beyond this ⇒ tip-over fault, stop (it rolls over near 60°)"},
    {.key = "tip_over_pitch_rad", .field = field<&SafetyParams::tip_over_pitch_rad>, .min = 0.01,
     .max = kPi / 2, .unit = "rad", .source = "docs/decisions.md",
     .about = "the chassis' mean pitch beyond this ⇒ tip-over fault, stop"},
    {.key = "tip_over_time_constant_s", .field = field<&SafetyParams::tip_over_time_constant_s>,
     .min = 0.01, .max = 10.0, .unit = "s", .source = "docs/decisions.md",
     .about = "the accelerometer's mean for the tip-over check: shorter trips on the blades' shaking"},
    {.key = "stuck_time_s", .field = field<&SafetyParams::stuck_time_s>, .min = 0.0, .max = 600.0,
     .unit = "s", .source = "docs/decisions.md",
     .about = "the centre wheels stalled under a command this long ⇒ stuck fault, stop (0: off)"},
    {.key = "stuck_min_command_radps", .field = field<&SafetyParams::stuck_min_command_radps>,
     .min = 0.01, .max = 3.0, .unit = "rad/s", .source = "docs/decisions.md",
     .about = "the centre wheels' mean |ν| that counts as driving for the stuck check"},
    {.key = "stuck_turning_share", .field = field<&SafetyParams::stuck_turning_share>, .min = 0.0,
     .max = 0.99, .source = "docs/decisions.md",
     .about = "stalled: the centre wheels turn at most this share of their command (Σ|w| ≤ s·Σ|ν|)"},
    {.key = "stuck_min_yaw_rate_radps", .field = field<&SafetyParams::stuck_min_yaw_rate_radps>,
     .min = 0.01, .max = 3.0, .unit = "rad/s", .source = "docs/decisions.md",
     .about = "a rover the gyro sees turning faster than this is not stuck"},
    {.key = "joint_blocked_time_s", .field = field<&SafetyParams::joint_blocked_time_s>,
     .min = 0.0, .max = 600.0, .unit = "s", .source = "docs/decisions.md",
     .about = "a joint stalled under a command this long ⇒ joint blocked fault, stop (0: off)"},
    {.key = "joint_blocked_min_command_radps",
     .field = field<&SafetyParams::joint_blocked_min_command_radps>, .min = 0.01, .max = 3.0,
     .unit = "rad/s", .source = "docs/decisions.md",
     .about = "a joint's |ν| that counts as driving it for the blocked check"},
    {.key = "joint_blocked_turning_share", .field = field<&SafetyParams::joint_blocked_turning_share>,
     .min = 0.0, .max = 0.99, .source = "docs/decisions.md",
     .about = "stalled: the joint turns at most this share of its command (|w| ≤ s·|ν|)"},
};

constexpr ParamSpec kNavigation[] = {
    {.key = "cruise_speed_mps", .field = field<&NavigationParams::cruise_speed_mps>, .min = 0.005,
     .max = 1.0, .unit = "m/s", .source = "docs/decisions.md",
     .about = "a move's speed between its ramps (m1's v1·r)"},
    {.key = "min_speed_mps", .field = field<&NavigationParams::min_speed_mps>, .min = 0.005,
     .max = 1.0, .unit = "m/s", .source = "docs/decisions.md",
     .about = "the slowest a leg creeps to its end"},
    {.key = "max_spin_radps", .field = field<&NavigationParams::max_spin_radps>, .min = 0.01,
     .max = 3.0, .unit = "rad/s", .source = "docs/decisions.md",
     .about = "m2's centre-wheel speed v2 turning on the spot"},
    {.key = "min_spin_radps", .field = field<&NavigationParams::min_spin_radps>, .min = 0.01,
     .max = 3.0, .unit = "rad/s", .source = "docs/decisions.md",
     .about = "the slowest v2 a turn creeps to its end with"},
    {.key = "heading_gain", .field = field<&NavigationParams::heading_gain>, .min = 0.01,
     .max = 100.0, .unit = "1/s", .source = "docs/decisions.md",
     .about = "k_ψ: v2 [rad/s] per radian of heading error"},
    {.key = "look_ahead_m", .field = field<&NavigationParams::look_ahead_m>, .min = 0.01,
     .max = 10.0, .unit = "m", .source = "docs/decisions.md",
     .about = "the heading aims back at the leg's line this far ahead"},
    {.key = "heading_tolerance_rad", .field = field<&NavigationParams::heading_tolerance_rad>,
     .min = 0.0005, .max = 0.5, .unit = "rad", .source = "docs/decisions.md",
     .about = "a turn that settles more than twice this off its heading is turned again"},
    {.key = "position_tolerance_m", .field = field<&NavigationParams::position_tolerance_m>,
     .min = 0.001, .max = 1.0, .unit = "m", .source = "docs/decisions.md",
     .about = "a leg ends within this along its line"},
    {.key = "turn_in_place_rad", .field = field<&NavigationParams::turn_in_place_rad>, .min = 0.01,
     .max = kPi, .unit = "rad", .source = "docs/decisions.md",
     .about = "goto turns on the spot first when a waypoint lies further off the heading"},
    {.key = "settle_s", .field = field<&NavigationParams::settle_s>, .min = 0.01, .max = 10.0,
     .unit = "s", .source = "docs/decisions.md",
     .about = "standing still this long ends a leg (the gyro learns its null meanwhile, (3.4))"},
    {.key = "still_yaw_rate_radps", .field = field<&NavigationParams::still_yaw_rate_radps>,
     .min = 0.001, .max = 1.0, .unit = "rad/s", .source = "docs/decisions.md",
     .about = "still: |ω| below this while the driver judges the rover standing"},
    {.key = "max_settle_s", .field = field<&NavigationParams::max_settle_s>, .min = 0.01,
     .max = 60.0, .unit = "s", .source = "docs/decisions.md",
     .about = "a leg's settling ends after this anyway"},
    {.key = "max_corrections", .field = field<&NavigationParams::max_corrections>, .min = 0,
     .max = 100, .source = "docs/decisions.md",
     .about = "legs driven again after ending more than twice their tolerance off, per mission"},
    {.key = "no_progress_s", .field = field<&NavigationParams::no_progress_s>, .min = 0.5,
     .max = 600.0, .unit = "s", .source = "docs/decisions.md",
     .about = "no progress (1 cm or 0.01 rad) this long aborts the mission"},
};

constexpr ParamSpec kConsole[] = {
    {.key = "listen", .field = field<&ConsoleParams::listen>, .max_length = 64,
     .about = "ADDR:PORT of the console's server; see the README before opening it to a network"},
    {.key = "token", .field = field<&ConsoleParams::token>, .max_length = 256,
     .about = "\"\": a fresh random token at every start (printed with the URL)"},
    {.key = "status_rate_hz", .field = field<&ConsoleParams::status_rate_hz>, .min = 1.0,
     .max = 64.0, .unit = "Hz", .about = "status messages per second to each console"},
    {.key = "allowed_hosts", .field = field<&ConsoleParams::allowed_hosts>, .max_count = 32,
     .max_length = 253,
     .about = "names the console is opened by, besides the listen address and localhost (DNS "
              "rebinding guard)"},
    {.key = "allowed_origins", .field = field<&ConsoleParams::allowed_origins>, .max_count = 32,
     .max_length = 300,
     .about = "other page origins that may open the WebSocket, e.g. a TLS reverse proxy's"},
};

constexpr SectionSpec kSchema[] = {
    table<&Configuration::params, &Params::geometry>("geometry", "chapter 3.1 table, Figure 3.3",
                                                     "The rover's dimensions", kGeometry),
    table<&Configuration::params, &Params::cycle>("cycle", "chapter 3.2",
                                                  "The communication cycle and the registers the "
                                                  "driver configures",
                                                  kCycle),
    table<&Configuration::params, &Params::motors>("motors", "chapters 3.2, 4.1, 4.2",
                                                   "The motors; vectors over the 8 motors in the "
                                                   "order of (3.1)",
                                                   kMotors),
    repeated<&Configuration::params, &Params::motor_curves>(
        "motor_curve", "Procedure 4.4",
        "W_icr(d), no-load speed over duty, one table per icr; odd for d < 0. Figures 3.6 and 4.2 "
        "are lost: W₅₁₁ is reconstructed through W(0.3) = 0.847, W⁻¹(2.429) ≈ 0.826 and W(1) = w",
        kMotorCurve),
    repeated<&Configuration::params, &Params::responses>(
        "response", "(4.4), Procedure 4.8",
        "δ^j of the motors' response, one table per (h, con); one for the configured cycle",
        kResponse),
    table<&Configuration::params, &Params::power>("power", "(4.5), chapter 6.1",
                                                  "Voltage drop and power management", kPower),
    table<&Configuration::params, &Params::load>("load", "(4.7)", "Load from torque, l ≈ τ·B",
                                                 kLoad),
    repeated<&Configuration::params, &Params::load_gains>(
        "load_gain", "(4.6), Procedure 4.13",
        "B±_icr(d), load per torque over duty, one table per icr; the driver's torque estimate τ "
        "uses the configured icr's. Figure 4.8 is lost: B rises below d = 0.3 by "
        "0.5·512/(icr+1) of (4.7)'s constants (docs/decisions.md)",
        kLoadGain),
    table<&Configuration::params, &Params::joints>("joints", "(5.3), (4.15), Procedure 4.17",
                                                   "The joints' bounds and control", kJoints),
    table<&Configuration::params, &Params::spin>("spin", "chapter 5.1",
                                                 "The wheel speeds of spinning", kSpin),
    table<&Configuration::params, &Params::load_distribution>(
        "load_distribution", "chapter 6.3", "Traction redistribution", kLoadDistribution),
    table<&Configuration::params, &Params::filters>(
        "filters", "chapters 3.3, 6.2.1", "The \"λ close to 1\" low-pass coefficients, per cycle",
        kFilters),
    table<&Configuration::params, &Params::sensors>("sensors", "chapter 3.3",
                                                    "µ8's sensors and their conversions", kSensors),
    table<&Configuration::params, &Params::operator_input>(
        "operator", "Remark 5.7", "What full deflection of the gamepad asks for", kOperator),
    table<&Configuration::params, &Params::gaits>(
        "gaits", "chapter 5.3", "Wheel walking (docs/design.md's gait tables)", kGaits),
    table<&Configuration::params, &Params::behaviours>(
        "behaviours", "chapter 6",
        "The autonomous behaviours; each can also be switched at run time", kBehaviours),
    table<&Configuration::params, &Params::safety>(
        "safety", "chapters 3.2, 3.3", "Duty rules, timeouts and the dead man's switch", kSafety),
    table<&Configuration::params, &Params::navigation>(
        "navigation", "Quote 2.3",
        "Missions for application software: turn, move, goto by dead reckoning", kNavigation),
    table<&Configuration::console>("console", "",
                                   "The operator console's link (src/link); command-line options "
                                   "override these",
                                   kConsole),
};

}  // namespace

std::span<const SectionSpec> param_schema() { return kSchema; }

const SectionSpec* find_section(std::string_view name) {
  for (const SectionSpec& section : kSchema) {
    if (section.name == name) return &section;
  }
  return nullptr;
}

}  // namespace marsokhod::config
