#include "driver/operator_commands.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace marsokhod::driver {
namespace {

std::string range_text(const NumberRange& range) {
  std::string text;
  if (range.min_open) {
    text = "(" + number_text(range.min) + ", " + number_text(range.max) + "]";
  } else if (range.min == -range.max) {
    text = "\u2212" + number_text(range.max) + ".." + number_text(range.max);
  } else {
    text = "[" + number_text(range.min) + ", " + number_text(range.max) + "]";
  }
  if (!range.unit.empty()) text += " " + std::string(range.unit);
  return text;
}

std::optional<CommandError> check_joint_target(std::string_view field,
                                               const std::optional<double>& target, double min,
                                               double max) {
  if (!target) return std::nullopt;
  return check_number(field, *target, {min, max, false, "rad (5.3)"});
}

}  // namespace

std::string number_text(double value) {
  if (std::isfinite(value) && value == std::trunc(value) && std::abs(value) < 1e15) {
    return std::to_string(static_cast<long long>(value));
  }
  std::array<char, 32> text{};
  const auto result =
      std::to_chars(text.data(), text.data() + text.size(), value, std::chars_format::general);
  return std::string(text.data(), result.ptr);
}

RuntimeSettings runtime_settings_from(const Params& params) {
  RuntimeSettings s;
  s.switches = behaviour::switches_from_params(params.behaviours, params.load_distribution);
  s.max_drop_v = params.power.max_drop_v;
  s.supply = params.power.supply;
  return s;
}

SettingsChange SettingsChange::all_of(const RuntimeSettings& s) {
  return {s.max_drop_v,
          s.switches.load_distribution,
          s.switches.power_management,
          s.switches.slant_response,
          s.switches.contract_on_turn,
          s.switches.axle_placement,
          s.speed_scale,
          s.supply};
}

RuntimeSettings SettingsChange::applied_to(RuntimeSettings settings) const {
  behaviour::BehaviourSwitches& w = settings.switches;
  settings.max_drop_v = max_drop_v.value_or(settings.max_drop_v);
  settings.speed_scale = speed_scale.value_or(settings.speed_scale);
  settings.supply = supply.value_or(settings.supply);
  w.load_distribution = load_distribution.value_or(w.load_distribution);
  w.power_management = power_management.value_or(w.power_management);
  w.slant_response = slant_response.value_or(w.slant_response);
  w.contract_on_turn = contract_on_turn.value_or(w.contract_on_turn);
  w.axle_placement = axle_placement.value_or(w.axle_placement);
  return settings;
}

std::optional<CommandError> check_number(std::string_view field, double value,
                                         const NumberRange& range) {
  const std::string name(field);
  if (!std::isfinite(value)) return CommandError{name, name + " is not a finite number"};
  const bool above_min = range.min_open ? value > range.min : value >= range.min;
  if (above_min && value <= range.max) return std::nullopt;
  return CommandError{name, name + ": " + number_text(value) + " is out of range; allowed " +
                                range_text(range)};
}

std::optional<CommandError> check_targets(const mobility::OperatorTargets& t,
                                          const Params& params) {
  const OperatorParams& o = params.operator_input;
  const double w = params.motors.max_no_load_speed_radps;
  struct Speed {
    std::string_view field;
    double value;
    double limit;
  };
  for (const Speed& s : {Speed{"v1", t.v1_radps, o.max_drive_speed_radps},
                         Speed{"v2", t.v2_radps, o.max_spin_speed_radps},
                         Speed{"v3", t.v3_radps, o.max_drift_speed_radps},
                         Speed{"v4", t.v4_radps, o.max_trench_speed_radps},
                         Speed{"v6", t.v6_radps, w}, Speed{"v7", t.v7_radps, w}}) {
    if (auto e = check_number(s.field, s.value, symmetric_range(s.limit, "rad/s"))) return e;
  }
  if (auto e = check_number("gait_speed", t.gait_speed, kGaitSpeedRange)) return e;
  const JointParams& j = params.joints;
  if (auto e = check_joint_target("front_joint_target", t.front_joint_target_rad,
                                  j.front_min_rad, j.front_max_rad)) {
    return e;
  }
  return check_joint_target("rear_joint_target", t.rear_joint_target_rad, j.rear_min_rad,
                            j.rear_max_rad);
}

std::optional<CommandError> check_gamepad(const mobility::GamepadState& gamepad) {
  for (std::size_t i = 0; i < gamepad.axes.size(); ++i) {
    const std::string field = "axes[" + std::to_string(i) + "]";
    if (auto e = check_number(field, gamepad.axes[i], kAxisRange)) return e;
  }
  return std::nullopt;
}

std::optional<CommandError> check_settings(const SettingsChange& change) {
  if (change.max_drop_v) {
    if (auto e = check_number("max_drop_v", *change.max_drop_v, kMaxDropRange)) return e;
  }
  if (change.speed_scale) {
    if (auto e = check_number("speed_scale", *change.speed_scale, kSpeedScaleRange)) return e;
  }
  return std::nullopt;
}

void validate(const RuntimeSettings& settings) {
  if (auto e = check_settings(SettingsChange::all_of(settings))) {
    throw std::invalid_argument(e->message);
  }
}

}  // namespace marsokhod::driver
