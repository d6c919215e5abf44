// The operator's commands as the driver takes them, whatever carried them (the console's
// WebSocket, a scenario file, a recording, the soak's script, a calibration bench): one input a
// cycle (OperatorInput) and the run-time settings (RuntimeSettings, changed by SettingsChange).
//
// Their ranges are here, once. The link checks a console's message against them before it
// answers (so the console hears at once what is wrong), the operator channel checks every input
// again whatever carried it (operator_channel.hpp), and Driver::set_runtime the settings. Their
// JSON, for the console and the recordings alike, is link/command_json.hpp.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "core/behaviour/switches.hpp"
#include "core/mobility/gamepad.hpp"
#include "core/navigation/mission.hpp"
#include "core/params.hpp"

namespace marsokhod::driver {

// One operator message: a gamepad reading, the targets of the mapping directly, a cmd_vel, a
// mission (turn, move, goto: core/navigation/mission.hpp) or a heartbeat — at most one of them.
struct OperatorInput {
  std::optional<mobility::GamepadState> gamepad;
  std::optional<mobility::OperatorTargets> targets;  // memory is ignored
  std::optional<navigation::VelocityCommand> velocity;  // a stream, like targets
  std::optional<navigation::MissionRequest> mission;    // starts a mission (once per message)
  bool heartbeat = false;     // keeps a running mission alive; neutral, moves nothing itself
  bool stop = false;          // all targets zero until a neutral input re-arms (operator_channel)
  bool clear_faults = false;  // acknowledge latched faults (silent controllers)
  std::string stop_reason;    // who stopped and why ("client 3 pressed STOP"); empty: "stop"
  bool operator==(const OperatorInput&) const = default;
};

// What the operator may change at run time (through the console), besides the targets.
struct RuntimeSettings {
  behaviour::BehaviourSwitches switches;
  double max_drop_v = 1.5;   // Υ of (6.3), (0, 10] V
  double speed_scale = 1.0;  // v1ᵈ…v4ᵈ are scaled by this ∈ [0, 1] (maximum speed)
  // What feeds the rover: on the tether the supply's current is kept within its limit
  // (core/behaviour/supply_current.hpp).
  SupplyKind supply = SupplyKind::kBattery;
  bool operator==(const RuntimeSettings&) const = default;
};
RuntimeSettings runtime_settings_from(const Params& params);

// Some of the settings (the console's configure, a scenario's [runtime]): a setting left out
// stays as it is.
struct SettingsChange {
  std::optional<double> max_drop_v;
  std::optional<LoadDistributionMode> load_distribution;
  std::optional<bool> power_management;
  std::optional<bool> slant_response;
  std::optional<bool> contract_on_turn;
  std::optional<bool> axle_placement;
  std::optional<double> speed_scale;
  std::optional<SupplyKind> supply;
  bool operator==(const SettingsChange&) const = default;

  // Every setting: `settings` as a change.
  static SettingsChange all_of(const RuntimeSettings& settings);
  // `settings` with the settings this change carries replaced.
  RuntimeSettings applied_to(RuntimeSettings settings) const;
};

// A closed interval [min, max], or (min, max] when min_open; `unit` follows it in messages.
struct NumberRange {
  double min = 0.0;
  double max = 0.0;
  bool min_open = false;
  std::string_view unit;
};
constexpr NumberRange symmetric_range(double limit, std::string_view unit) {
  return {-limit, limit, false, unit};
}

inline constexpr NumberRange kAxisRange = symmetric_range(1.0, "");       // a gamepad's axes
inline constexpr NumberRange kGaitSpeedRange = symmetric_range(1.0, "");  // s
inline constexpr NumberRange kMaxDropRange = {0.0, 10.0, true, "V"};      // Υ
inline constexpr NumberRange kSpeedScaleRange = {0.0, 1.0, false, ""};

// Why a command was refused: the field ("v1", "axes[1]", "max_drop_v") and a message that names
// it and says what is allowed ("v1: 2.3 is out of range; allowed −2.25..2.25 rad/s").
struct CommandError {
  std::string field;
  std::string message;
  bool operator==(const CommandError&) const = default;
};

// nullopt when `value` is finite and inside `range`.
std::optional<CommandError> check_number(std::string_view field, double value,
                                         const NumberRange& range);

// The ranges in force: |v1| ≤ max_drive_speed_radps, |v2| ≤ max_spin_speed_radps,
// |v3| ≤ max_drift_speed_radps, |v4| ≤ max_trench_speed_radps, |v6|, |v7| ≤ max_no_load_speed_radps, s ∈ [−1, 1], the joint
// position targets inside (5.3).
std::optional<CommandError> check_targets(const mobility::OperatorTargets& targets,
                                          const Params& params);
// Every axis in [−1, 1].
std::optional<CommandError> check_gamepad(const mobility::GamepadState& gamepad);
// Υ ∈ (0, 10] V, speed_scale ∈ [0, 1], for the settings the change carries.
std::optional<CommandError> check_settings(const SettingsChange& change);
// Throws std::invalid_argument with check_settings' message.
void validate(const RuntimeSettings& settings);

// "1.7", "2", "-0.25": the shortest text that reads back as the same double; whole numbers
// without ".0", as people write ranges.
std::string number_text(double value);

}  // namespace marsokhod::driver
