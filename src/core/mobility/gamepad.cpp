#include "core/mobility/gamepad.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "core/checks/checks.hpp"

namespace marsokhod::mobility {
namespace {

constexpr std::array<const char*, kGamepadAxisCount> kAxisNames = {
    "axis 0 (left stick x)", "axis 1 (left stick y)", "axis 2 (right stick x)",
    "axis 3 (right stick y)"};

void require_non_negative(double value, const char* field) {
  checks::law::require_finite(value, "OperatorParams", field);
  if (value < 0.0) {
    std::ostringstream message;
    message << "OperatorParams: " << field << " must be ≥ 0, got " << value
            << "; fix [operator] in config/marsokhod.toml";
    throw std::invalid_argument(message.str());
  }
}

// The gait the pressed buttons ask for; `current` if none or more than one is pressed. B (no
// gait) wins.
Gait selected_gait(const GamepadState& gamepad, Gait current) {
  if (gamepad.buttons[kButtonRight]) {
    return Gait::kNone;
  }
  constexpr std::array<std::pair<GamepadButton, Gait>, 5> kGaitButtons{{
      {kDpadUp, Gait::kRolking},
      {kDpadRight, Gait::kFrontWheelWalking},
      {kDpadDown, Gait::kWormLike},
      {kDpadLeft, Gait::kRearWheelWalking},
      {kButtonTop, Gait::kRolkingExtendedBase},
  }};
  Gait chosen = current;
  int pressed = 0;
  for (const auto& [button, gait] : kGaitButtons) {
    if (gamepad.buttons[button]) {
      chosen = gait;
      ++pressed;
    }
  }
  return pressed == 1 ? chosen : current;
}

// +speed if only `increase` is pressed, −speed if only `decrease`, else 0.
double button_pair(bool increase, bool decrease, double speed) {
  return (increase ? speed : 0.0) - (decrease ? speed : 0.0);
}

}  // namespace

double apply_dead_zone(double value, double dead_zone, const char* axis_name) {
  if (std::isnan(value) || std::abs(value) > 1.0) {
    std::ostringstream message;
    message << "map_gamepad: " << axis_name << " must lie in [-1, 1], got " << value
            << "; the gamepad reading is broken (check the browser's standard mapping)";
    throw std::invalid_argument(message.str());
  }
  const double magnitude = std::abs(value);
  if (magnitude < dead_zone) {
    return 0.0;
  }
  return std::copysign((magnitude - dead_zone) / (1.0 - dead_zone), value);
}

void validate(const OperatorParams& params) {
  require_non_negative(params.dead_zone, "dead_zone");
  if (!(params.dead_zone < 1.0)) {
    throw std::invalid_argument(
        "OperatorParams: dead_zone must lie in [0, 1) or no deflection is ever read; fix "
        "[operator] in config/marsokhod.toml");
  }
  require_non_negative(params.max_drive_speed_radps, "max_drive_speed_radps");
  require_non_negative(params.max_spin_speed_radps, "max_spin_speed_radps");
  require_non_negative(params.max_drift_speed_radps, "max_drift_speed_radps");
  require_non_negative(params.max_trench_speed_radps, "max_trench_speed_radps");
  require_non_negative(params.joint_button_speed_radps, "joint_button_speed_radps");
  require_non_negative(params.calibration_duty, "calibration_duty");
  if (params.calibration_duty > 1.0) {
    throw std::invalid_argument(
        "OperatorParams: calibration_duty must be at most 1 (a duty cycle; Procedure 4.3 uses "
        "0.08)");
  }
}

OperatorTargets map_gamepad(const GamepadState& gamepad, const OperatorParams& params,
                            const GamepadMemory& before) {
  validate(params);
  std::array<double, kGamepadAxisCount> axes{};
  for (std::size_t i = 0; i < kGamepadAxisCount; ++i) {
    axes[i] = apply_dead_zone(gamepad.axes[i], params.dead_zone, kAxisNames[i]);
  }
  OperatorTargets targets;
  const bool select = gamepad.buttons[kSelect];
  targets.calibration_mode = before.calibration_mode != (select && !before.select_was_pressed);
  targets.joint_buttons = {gamepad.buttons[kLeftBumper], gamepad.buttons[kLeftTrigger],
                           gamepad.buttons[kRightBumper], gamepad.buttons[kRightTrigger]};
  if (!targets.calibration_mode) {
    // −0.0 would be harmless but odd in logs: 0 − x keeps a released stick at +0.
    targets.v1_radps = 0.0 - axes[kLeftStickY] * params.max_drive_speed_radps;
    targets.v2_radps = 0.0 - axes[kLeftStickX] * params.max_spin_speed_radps;
    targets.v3_radps = button_pair(gamepad.buttons[kButtonLeft], gamepad.buttons[kButtonBottom],
                                   params.max_drift_speed_radps);
    targets.v4_radps = axes[kRightStickX] * params.max_trench_speed_radps;
    targets.gait_speed = 0.0 - axes[kRightStickY];
    const JointButtons& joint = targets.joint_buttons;
    targets.v6_radps =
        button_pair(joint.contract_front, joint.extend_front, params.joint_button_speed_radps);
    targets.v7_radps =
        button_pair(joint.extend_rear, joint.contract_rear, params.joint_button_speed_radps);
    targets.gait = selected_gait(gamepad, before.gait);
  }
  targets.memory = {targets.calibration_mode, targets.gait, select};
  return targets;
}

std::array<double, 2> calibration_duties(const JointButtons& buttons,
                                         const OperatorParams& params) {
  validate(params);
  return {button_pair(buttons.contract_front, buttons.extend_front, params.calibration_duty),
          button_pair(buttons.extend_rear, buttons.contract_rear, params.calibration_duty)};
}

}  // namespace marsokhod::mobility
