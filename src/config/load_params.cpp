#include "config/load_params.hpp"

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <utility>

#include "config/calibration.hpp"
#include "config/config_reader.hpp"

namespace marsokhod::config {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kLambdaMax = 0.999999;  // a low-pass with λ = 1 would never move

std::string join(const std::string& source, const std::vector<std::string>& problems) {
  std::string text = source + ": " + std::to_string(problems.size()) + " configuration problem" +
                     (problems.size() == 1 ? "" : "s");
  for (const auto& p : problems) text += "\n  " + p;
  return text;
}

GeometryParams read_geometry(ConfigReader r) {
  GeometryParams g;
  g.joint_to_exterior_axle_m = r.number("joint_to_exterior_axle_m", 0.01, 1.0);
  g.center_axle_to_joint_m = r.number("center_axle_to_joint_m", 0.01, 2.0);
  g.wheel_radius_m = r.number("wheel_radius_m", 0.05, 0.5);
  g.track_width_m = r.number("track_width_m", 0.1, 3.0);
  g.blade_inclination_rad = r.number("blade_inclination_rad", 0.0, kPi / 2);
  r.reject_unknown_keys();
  return g;
}

CycleParams read_cycle(ConfigReader r) {
  CycleParams c;
  c.period_s = r.number("period_s", 0.001, 0.5);
  c.con = r.integer("con", 0, 255);
  c.icr = r.integer("icr", 255, 2047);
  r.reject_unknown_keys();
  return c;
}

MotorParams read_motors(ConfigReader r) {
  MotorParams m;
  m.encoder_pulses_per_rev = r.integer("encoder_pulses_per_rev", 1, 100'000'000);
  m.max_no_load_speed_radps = r.number("max_no_load_speed_radps", 0.1, 100.0);
  m.nominal_supply_v = r.number("nominal_supply_v", 1.0, 100.0);
  m.scale = r.fixed_numbers<kMotorCount>("scale", 0.5, 1.5);
  m.backlash_rad = r.fixed_numbers<kMotorCount>("backlash_rad", 0.0, 1.0);
  m.initial_position_rad = r.fixed_numbers<kMotorCount>("initial_position_rad", -10.0, 10.0);
  r.reject_unknown_keys();
  return m;
}

std::vector<MotorCurveParams> read_motor_curves(ConfigReader& root) {
  std::vector<MotorCurveParams> curves;
  for (ConfigReader& r : root.tables("motor_curve", 1)) {
    MotorCurveParams c;
    c.icr = r.integer("icr", 255, 2047);
    c.duty = r.numbers("duty", 0.0, 1.0, 2, 256);
    c.no_load_speed_radps = r.numbers("no_load_speed_radps", 0.0, 100.0, 2, 256);
    r.reject_unknown_keys();
    curves.push_back(std::move(c));
  }
  return curves;
}

std::vector<ResponseParams> read_responses(ConfigReader& root) {
  std::vector<ResponseParams> responses;
  for (ConfigReader& r : root.tables("response", 1)) {
    ResponseParams p;
    p.period_s = r.number("period_s", 0.001, 0.5);
    p.con = r.integer("con", 0, 255);
    p.delta = r.numbers("delta", -2.0, 2.0, 1, 256);
    r.reject_unknown_keys();
    responses.push_back(std::move(p));
  }
  return responses;
}

PowerParams read_power(ConfigReader r) {
  PowerParams p;
  p.duty_drop_v = r.number("duty_drop_v", 0.0, 10.0);
  p.load_drop_v_s2_per_rad2 = r.number("load_drop_v_s2_per_rad2", 0.0, 10.0);
  p.max_drop_v = r.number("max_drop_v", 0.01, 10.0);
  p.brownout_v = r.number("brownout_v", 0.0, 100.0);
  r.reject_unknown_keys();
  return p;
}

LoadParams read_load(ConfigReader r) {
  LoadParams l;
  l.gain_same_sign_radps_per_nm = r.number("gain_same_sign_radps_per_nm", 1e-6, 10.0);
  l.gain_opposite_sign_radps_per_nm = r.number("gain_opposite_sign_radps_per_nm", 1e-6, 10.0);
  r.reject_unknown_keys();
  return l;
}

JointParams read_joints(ConfigReader r) {
  JointParams j;
  j.front_min_rad = r.number("front_min_rad", -kPi, 0.0);
  j.front_max_rad = r.number("front_max_rad", -kPi, 0.0);
  j.rear_min_rad = r.number("rear_min_rad", 0.0, kPi);
  j.rear_max_rad = r.number("rear_max_rad", 0.0, kPi);
  j.control_rate_per_s = r.number("control_rate_per_s", 0.001, 100.0);
  j.control_speed_fraction = r.number("control_speed_fraction", 0.01, 1.0);
  j.target_tolerance_rad = r.number("target_tolerance_rad", 0.001, 1.0);
  j.backlash_uncertainty = r.number("backlash_uncertainty", 0.0, 0.5);
  r.reject_unknown_keys();
  return j;
}

SpinParams read_spin(ConfigReader r) {
  SpinParams s;
  s.slope_per_m = r.number("slope_per_m", 0.0, 100.0);
  s.offset = r.number("offset", -10.0, 10.0);
  r.reject_unknown_keys();
  return s;
}

LoadDistributionParams read_load_distribution(ConfigReader r) {
  LoadDistributionParams d;
  const std::string mode = r.choice("mode", {"off", "v", "s"});
  d.mode = mode == "v"   ? LoadDistributionMode::kVariance
           : mode == "s" ? LoadDistributionMode::kSlip
                         : LoadDistributionMode::kOff;
  d.gain_per_radps = r.number("gain_per_radps", 0.0, 100.0);
  d.max_correction_radps = r.number("max_correction_radps", 0.0, 3.0);
  r.reject_unknown_keys();
  return d;
}

FilterParams read_filters(ConfigReader r) {
  FilterParams f;
  f.gyro_null_lambda = r.number("gyro_null_lambda", 0.0, kLambdaMax);
  f.reference_voltage_lambda = r.number("reference_voltage_lambda", 0.0, kLambdaMax);
  f.gravity_lambda = r.number("gravity_lambda", 0.0, kLambdaMax);
  r.reject_unknown_keys();
  return f;
}

SensorParams read_sensors(ConfigReader r) {
  SensorParams s;
  s.gravity_mps2 = r.number("gravity_mps2", 1.0, 30.0);
  s.gyro_radps_per_count = r.number("gyro_radps_per_count", 1e-6, 1.0);
  s.gyro_null_typ_counts = r.number("gyro_null_typ_counts", 0.0, 1023.0);
  const auto minus_g = r.fixed_numbers<3>("accelerometer_minus_g_counts", 0.0, 1023.0);
  const auto plus_g = r.fixed_numbers<3>("accelerometer_plus_g_counts", 0.0, 1023.0);
  for (std::size_t i = 0; i < 3; ++i) s.accelerometer[i] = {minus_g[i], plus_g[i]};
  s.tilt_front = {r.number("tilt_front_rad_per_count", -1.0, 1.0),
                  r.number("tilt_front_offset_rad", -10.0, 10.0)};
  s.tilt_rear = {r.number("tilt_rear_rad_per_count", -1.0, 1.0),
                 r.number("tilt_rear_offset_rad", -10.0, 10.0)};
  s.supply = {r.number("supply_v_per_count", 1e-6, 1.0), r.number("supply_offset_v", -100.0, 100.0)};
  r.reject_unknown_keys();
  return s;
}

OperatorParams read_operator(ConfigReader r) {
  OperatorParams o;
  o.dead_zone = r.number("dead_zone", 0.0, 0.9);
  o.max_drive_speed_radps = r.number("max_drive_speed_radps", 0.0, 100.0);
  o.max_spin_speed_radps = r.number("max_spin_speed_radps", 0.0, 100.0);
  o.max_trench_speed_radps = r.number("max_trench_speed_radps", 0.0, 100.0);
  o.joint_button_speed_radps = r.number("joint_button_speed_radps", 0.0, 100.0);
  o.calibration_duty = r.number("calibration_duty", 0.0, 0.5);
  o.drive_rate_per_s = r.number("drive_rate_per_s", 0.01, 100.0);
  r.reject_unknown_keys();
  return o;
}

GaitParams read_gaits(ConfigReader r) {
  GaitParams g;
  g.extended_rad = r.number("extended_rad", 0.0, kPi);
  g.max_joint_speed_fraction = r.number("max_joint_speed_fraction", 0.01, 1.0);
  r.reject_unknown_keys();
  return g;
}

BehaviourParams read_behaviours(ConfigReader r) {
  BehaviourParams b;
  b.power_management = r.boolean("power_management");
  b.slant_response = r.boolean("slant_response");
  b.contract_on_turn = r.boolean("contract_on_turn");
  b.axle_placement = r.boolean("axle_placement");
  b.slant_deadband_rad = r.number("slant_deadband_rad", 0.0, 0.5);
  b.axle_placement_load_radps = r.number("axle_placement_load_radps", 0.0, 100.0);
  b.axle_placement_speed_radps = r.number("axle_placement_speed_radps", 0.0, 100.0);
  b.axle_placement_rate_per_s = r.number("axle_placement_rate_per_s", 0.0, 1000.0);
  r.reject_unknown_keys();
  return b;
}

SafetyParams read_safety(ConfigReader r) {
  SafetyParams s;
  s.operator_timeout_s = r.number("operator_timeout_s", 0.05, 1.0);  // longer: a lost link drives on too long
  s.dead_man_dog = r.integer("dead_man_dog", 0, 255);
  s.max_duty_step = r.number("max_duty_step", 0.001, 2.0);
  s.direction_change_duty = r.number("direction_change_duty", 0.0, 0.2);
  s.missed_responses_limit = r.integer("missed_responses_limit", 1, 1000);
  r.reject_unknown_keys();
  return s;
}

ConsoleParams read_console(ConfigReader r) {
  ConsoleParams c;
  c.listen = r.text("listen", 64);
  c.token = r.text("token", 256);
  c.status_rate_hz = r.number("status_rate_hz", 1.0, 64.0);
  c.allowed_hosts = r.texts("allowed_hosts", 32, 253);
  c.allowed_origins = r.texts("allowed_origins", 32, 300);
  r.reject_unknown_keys();
  return c;
}

}  // namespace

ConfigError::ConfigError(const std::string& source, std::vector<std::string> problems)
    : std::runtime_error(join(source, problems)), problems_(std::move(problems)) {}

Params parse_params(std::string_view toml_text, const std::string& source) {
  toml::table root;
  try {
    root = toml::parse(toml_text, source);
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << "line " << e.source().begin.line << ", column " << e.source().begin.column
        << ": TOML syntax error: " << e.description();
    throw ConfigError(source, {msg.str()});
  }
  return params_from_table(root, source);
}

Params params_from_table(const toml::table& root, const std::string& source) {
  std::vector<std::string> problems;
  ConfigReader r(&root, "", problems);
  Params p;
  p.geometry = read_geometry(r.table("geometry"));
  p.cycle = read_cycle(r.table("cycle"));
  p.motors = read_motors(r.table("motors"));
  p.motor_curves = read_motor_curves(r);
  p.responses = read_responses(r);
  p.power = read_power(r.table("power"));
  p.load = read_load(r.table("load"));
  p.joints = read_joints(r.table("joints"));
  p.spin = read_spin(r.table("spin"));
  p.load_distribution = read_load_distribution(r.table("load_distribution"));
  p.filters = read_filters(r.table("filters"));
  p.sensors = read_sensors(r.table("sensors"));
  p.operator_input = read_operator(r.table("operator"));
  p.gaits = read_gaits(r.table("gaits"));
  p.behaviours = read_behaviours(r.table("behaviours"));
  p.safety = read_safety(r.table("safety"));
  p.console = read_console(r.table("console"));
  r.reject_unknown_keys();
  if (problems.empty()) problems = consistency_problems(p);
  if (!problems.empty()) throw ConfigError(source, std::move(problems));
  return p;
}

Params load_params(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw ConfigError(file.string(), {"cannot open the file: check the path (the default is "
                                      "config/marsokhod.toml in the source tree)"});
  }
  std::ostringstream text;
  text << in.rdbuf();
  return parse_params(text.str(), file.string());
}

}  // namespace marsokhod::config
