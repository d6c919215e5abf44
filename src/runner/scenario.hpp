// A scenario file (TOML): terrain, faults, a timeline of operator inputs, phases and checks.
//
//   name = "straight-and-spin"            # defaults to the file name
//   description = "Figures 3.5/3.8: …"
//   duration_s = 16.0
//   seed = 1                             # --seed overrides
//   [sim]      supply = "battery"|"tether", nominal_unit = false, state_of_charge = 0.8
//   [terrain]  … see sim/physics/terrain.hpp
//   [runtime]  max_drop_v, speed_scale, load_distribution, behaviours = {…}   (at t = 0)
//   [[input]]  t = 4.0, then one of: targets = {v1 = 1.5, …} | gamepad = {axes, buttons}
//              | silent = true (the operator says nothing from t on) | stop = true;
//              a targets/gamepad input is sent every cycle until the next [[input]]
//   [[fault]]  t = 4.0, then any of: wheel_blocked = [0], wheel_no_contact = [2],
//              joint_jammed = [0] (0 the front joint, 1 the rear),
//              silent = [3], frame_loss = 0.1, lost_pulses = {motor = 2, fraction = 0.3},
//              battery_sag_ohm = 0.5, brownout = true, driver_halt = true, clear = true
//   [[runtime_change]] t = 10.0, then the [runtime] keys
//   [[phase]]  name = "short", from_s = 4.0, to_s = 9.0
//              A time window [from_s, to_s) with metrics of its own, named "PHASE.metric"
//              (metrics.hpp lists them): "short.yaw_rate_mean_radps". Names are letters, digits,
//              '_' and '-'; phases may overlap; to_s ≤ duration_s.
//   [[check]]  name = "…", metric = "distance_m", min = 1.0, max = 3.0   (either bound optional)
//              or, instead of metric, ratio_of = ["short.yaw_rate_mean_radps",
//              "long.yaw_rate_mean_radps"]: the check's value is the first metric divided by
//              the second (to compare phases). Every metric named must exist (metrics.hpp).
// Every key is checked: an unknown key, a wrong type or a value out of range is an error naming
// the key and its line.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "driver/operator_commands.hpp"
#include "sim/rover/simulated_rover.hpp"

namespace marsokhod::runner {

struct InputEvent {
  double t_s = 0.0;
  std::optional<driver::OperatorInput> input;  // none: the operator is silent from t on
};

struct FaultEvent {
  double t_s = 0.0;
  std::vector<std::size_t> wheel_blocked, wheel_no_contact, silent, joint_jammed;
  std::optional<double> frame_loss;
  std::optional<std::pair<std::size_t, double>> lost_pulses;
  std::optional<double> battery_sag_ohm;
  bool brownout = false;
  bool driver_halt = false;  // the driver stops stepping (a crash): µ8 must stop the motors
  bool clear = false;        // every fault off first
};

struct RuntimeEvent {
  double t_s = 0.0;
  nlohmann::json settings;  // the [runtime] keys, applied with runtime_settings_from_json
};

struct Phase {
  std::string name;
  double from_s = 0.0;
  double to_s = 0.0;
};

struct Check {
  std::string name;
  std::string metric;  // or, with ratio_of, "A / B"
  std::optional<std::pair<std::string, std::string>> ratio_of;  // the value is A / B
  std::optional<double> min, max;
};

struct Scenario {
  std::string name;
  std::string description;
  std::filesystem::path file;
  double duration_s = 10.0;
  std::uint64_t seed = 1;
  sim::SimOptions sim;
  std::optional<double> state_of_charge;
  nlohmann::json runtime = nlohmann::json::object();
  std::vector<InputEvent> inputs;
  std::vector<FaultEvent> faults;
  std::vector<RuntimeEvent> runtime_changes;
  std::vector<Phase> phases;
  std::vector<Check> checks;
};

// Throws std::invalid_argument with "FILE: key: what is wrong (line N)".
Scenario load_scenario(const std::filesystem::path& file);
// The same for a file's text (`file` names it in errors and anchors the terrain's image paths).
Scenario parse_scenario(std::string_view text, const std::filesystem::path& file);

// The scenario files shipped in a folder (name → path), sorted by name.
std::vector<std::pair<std::string, std::filesystem::path>> list_scenarios(
    const std::filesystem::path& folder);

}  // namespace marsokhod::runner
