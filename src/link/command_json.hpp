// The operator's commands (driver/operator_commands.hpp) as JSON: one codec for the console's
// messages (operator_message.hpp) and for the recordings and scenario files (operator.jsonl,
// [[input]], [runtime]), so that a field has the same key, type and error message everywhere.
//
// Reading is strict: an unknown key, a wrong type, an array of the wrong size is a FieldError
// (json_fields.hpp, an std::invalid_argument) naming the field by its path ("targets.v1",
// "behaviours.slant_response"). Ranges: the settings' are checked always; the gamepad's and the
// targets' when the reader is given the Params in force — the console's messages, so that the
// console hears at once what is wrong. Recordings are read as they were written (an input the
// driver refused must reach it again in replay); the driver checks them (operator_channel.hpp).
#pragma once

#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/mobility/gamepad.hpp"
#include "core/params.hpp"
#include "driver/operator_commands.hpp"

namespace marsokhod::link {

// How to read one JSON object. The readers read their keys and leave the others to the caller,
// who rejects the unknown ones (json_fields.hpp) with the codec's keys (gamepad_keys, …) and its
// own ("type", "seq").
struct Reading {
  std::string_view prefix;         // put before each field in errors: "" or "targets."
  std::string_view what;           // the object in errors: "a gamepad message", "gamepad"
  const Params* ranges = nullptr;  // check the ranges in force; nullptr: types only
};

// {"axes":[4 numbers],"buttons":[17 booleans]} (W3C standard mapping), both required.
std::vector<std::string_view> gamepad_keys();
mobility::GamepadState read_gamepad(const nlohmann::json& object, const Reading& how);
void write_gamepad(const mobility::GamepadState& gamepad, nlohmann::json& object);

// The console sends v1 v2 v3 v4 v6 v7 gait gait_speed calibration_mode; a recording (and a
// scenario) also joint_buttons [LB, LT, RB, RT], front_joint_target and rear_joint_target (rad).
enum class TargetKeys { kConsole, kRecording };
std::vector<std::string_view> target_keys(TargetKeys keys);
// A key left out is 0, "none", false, no joint target.
mobility::OperatorTargets read_targets(const nlohmann::json& object, TargetKeys keys,
                                       const Reading& how);
// Every key of `keys` (the joint targets only when set).
void write_targets(const mobility::OperatorTargets& targets, TargetKeys keys,
                   nlohmann::json& object);

// cmd_vel: {"v_mps":…,"yaw_radps":…}, both required; with ranges, inside check_velocity's.
std::vector<std::string_view> velocity_keys();
navigation::VelocityCommand read_velocity(const nlohmann::json& object, const Reading& how);
void write_velocity(const navigation::VelocityCommand& command, nlohmann::json& object);

// A mission: {"kind":"turn","angle_rad":…} | {"kind":"move","distance_m":…} |
// {"kind":"goto","waypoints":[{"x_m":…,"y_m":…},…]}; a key of another kind is an error. Any kind
// may add "settle_s" (its standing after each leg, in s). The limits of check_request are checked
// always (they do not depend on the configuration).
std::vector<std::string_view> mission_keys();
navigation::MissionRequest read_mission(const nlohmann::json& object, const Reading& how);
void write_mission(const navigation::MissionRequest& request, nlohmann::json& object);

// {"max_drop_v":…,"load_distribution":"off"|"v"|"s","behaviours":{"power_management":…,
// "slant_response":…,"contract_on_turn":…,"axle_placement":…},"speed_scale":…}: the keys given.
std::vector<std::string_view> settings_keys();
driver::SettingsChange read_settings_change(const nlohmann::json& object, const Reading& how);
void write_settings_change(const driver::SettingsChange& change, nlohmann::json& object);

// A recording's and a scenario's operator input: {"gamepad":{…},"targets":{…},"velocity":{…},
// "mission":{…},"heartbeat":true,"stop":true,"stop_reason":"…","clear_faults":true}, each key
// only when set.
nlohmann::json operator_input_json(const driver::OperatorInput& input);
driver::OperatorInput operator_input_from_json(const nlohmann::json& json);

// A recording's "runtime" (every key) and a scenario's [runtime] (some: the others stay as in
// `base`).
nlohmann::json runtime_settings_json(const driver::RuntimeSettings& settings);
driver::RuntimeSettings runtime_settings_from_json(const nlohmann::json& json,
                                                   const driver::RuntimeSettings& base);

std::string_view load_distribution_id(LoadDistributionMode mode);

}  // namespace marsokhod::link
