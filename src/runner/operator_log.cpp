#include "runner/operator_log.hpp"

#include <array>
#include <stdexcept>
#include <utility>

namespace marsokhod::runner {
namespace {

using nlohmann::json;
using mobility::Gait;


template <class T>
T field(const json& j, const char* key, const std::string& where, T fallback) {
  if (!j.contains(key)) return fallback;
  try {
    return j.at(key).get<T>();
  } catch (const json::exception&) {
    throw std::invalid_argument(where + key + ": " + j.at(key).dump() + " has the wrong type");
  }
}

void reject_unknown(const json& j, std::initializer_list<const char*> known, const std::string& where) {
  for (const auto& [key, value] : j.items()) {
    bool ok = false;
    for (const char* k : known) ok = ok || key == k;
    if (!ok) throw std::invalid_argument(where + key + ": unknown field");
  }
}

mobility::OperatorTargets targets_from_json(const json& j) {
  if (!j.is_object()) throw std::invalid_argument("targets: expected an object");
  reject_unknown(j, {"v1", "v2", "v4", "v6", "v7", "gait", "gait_speed", "calibration_mode",
                     "joint_buttons", "front_joint_target", "rear_joint_target"}, "targets.");
  mobility::OperatorTargets t;
  t.v1_radps = field(j, "v1", "targets.", 0.0);
  t.v2_radps = field(j, "v2", "targets.", 0.0);
  t.v4_radps = field(j, "v4", "targets.", 0.0);
  t.v6_radps = field(j, "v6", "targets.", 0.0);
  t.v7_radps = field(j, "v7", "targets.", 0.0);
  t.gait = gait_from_key(field<std::string>(j, "gait", "targets.", "none"));
  t.gait_speed = field(j, "gait_speed", "targets.", 0.0);
  t.calibration_mode = field(j, "calibration_mode", "targets.", false);
  if (j.contains("front_joint_target")) t.front_joint_target_rad = field(j, "front_joint_target", "targets.", 0.0);
  if (j.contains("rear_joint_target")) t.rear_joint_target_rad = field(j, "rear_joint_target", "targets.", 0.0);
  if (j.contains("joint_buttons")) {
    const auto b = field<std::array<bool, 4>>(j, "joint_buttons", "targets.", {});
    t.joint_buttons = {b[0], b[1], b[2], b[3]};
  }
  return t;
}

}  // namespace

Gait gait_from_key(const std::string& key) {
  if (const auto gait = mobility::gait_from_id(key)) return *gait;
  throw std::invalid_argument("gait: \"" + key +
                              "\" is not a gait; expected none, rolking, front-wheel-walking, "
                              "rear-wheel-walking, worm-like or rolking-extended-base");
}

json to_json(const driver::OperatorInput& input) {
  json j = json::object();
  if (input.gamepad) j["gamepad"] = {{"axes", input.gamepad->axes}, {"buttons", input.gamepad->buttons}};
  if (input.targets) {
    const auto& t = *input.targets;
    json tj = {{"v1", t.v1_radps}, {"v2", t.v2_radps}, {"v4", t.v4_radps}, {"v6", t.v6_radps},
               {"v7", t.v7_radps}, {"gait", std::string(mobility::gait_id(t.gait))}, {"gait_speed", t.gait_speed},
               {"calibration_mode", t.calibration_mode}};
    const auto& b = t.joint_buttons;
    tj["joint_buttons"] = {b.contract_front, b.extend_front, b.contract_rear, b.extend_rear};
    if (t.front_joint_target_rad) tj["front_joint_target"] = *t.front_joint_target_rad;
    if (t.rear_joint_target_rad) tj["rear_joint_target"] = *t.rear_joint_target_rad;
    j["targets"] = tj;
  }
  if (input.stop) j["stop"] = true;
  if (!input.stop_reason.empty()) j["stop_reason"] = input.stop_reason;
  if (input.clear_faults) j["clear_faults"] = true;
  return j;
}

driver::OperatorInput operator_input_from_json(const json& j) {
  if (!j.is_object()) throw std::invalid_argument("input: expected an object");
  reject_unknown(j, {"gamepad", "targets", "stop", "clear_faults", "stop_reason"}, "input.");
  driver::OperatorInput in;
  if (j.contains("gamepad")) {
    const json& g = j.at("gamepad");
    reject_unknown(g, {"axes", "buttons"}, "gamepad.");
    mobility::GamepadState pad;
    pad.axes = field(g, "axes", "gamepad.", pad.axes);
    pad.buttons = field(g, "buttons", "gamepad.", pad.buttons);
    in.gamepad = pad;
  }
  if (j.contains("targets")) in.targets = targets_from_json(j.at("targets"));
  in.stop = field(j, "stop", "input.", false);
  in.clear_faults = field(j, "clear_faults", "input.", false);
  in.stop_reason = field<std::string>(j, "stop_reason", "input.", "");
  return in;
}

json to_json(const driver::RuntimeSettings& s) {
  const char* mode = s.switches.load_distribution == LoadDistributionMode::kVariance ? "v"
                     : s.switches.load_distribution == LoadDistributionMode::kSlip   ? "s"
                                                                                     : "off";
  return {{"max_drop_v", s.max_drop_v},
          {"speed_scale", s.speed_scale},
          {"load_distribution", mode},
          {"behaviours",
           {{"power_management", s.switches.power_management},
            {"slant_response", s.switches.slant_response},
            {"contract_on_turn", s.switches.contract_on_turn},
            {"axle_placement", s.switches.axle_placement}}}};
}

driver::RuntimeSettings runtime_settings_from_json(const json& j, driver::RuntimeSettings s) {
  if (!j.is_object()) throw std::invalid_argument("runtime: expected an object");
  reject_unknown(j, {"max_drop_v", "speed_scale", "load_distribution", "behaviours"}, "runtime.");
  s.max_drop_v = field(j, "max_drop_v", "runtime.", s.max_drop_v);
  s.speed_scale = field(j, "speed_scale", "runtime.", s.speed_scale);
  const std::string mode = field<std::string>(j, "load_distribution", "runtime.", "keep");
  if (mode == "off") s.switches.load_distribution = LoadDistributionMode::kOff;
  else if (mode == "v") s.switches.load_distribution = LoadDistributionMode::kVariance;
  else if (mode == "s") s.switches.load_distribution = LoadDistributionMode::kSlip;
  else if (mode != "keep") throw std::invalid_argument("runtime.load_distribution: \"" + mode + "\"; expected off, v or s");
  if (j.contains("behaviours")) {
    const json& b = j.at("behaviours");
    reject_unknown(b, {"power_management", "slant_response", "contract_on_turn", "axle_placement"},
                   "runtime.behaviours.");
    auto& w = s.switches;
    w.power_management = field(b, "power_management", "runtime.behaviours.", w.power_management);
    w.slant_response = field(b, "slant_response", "runtime.behaviours.", w.slant_response);
    w.contract_on_turn = field(b, "contract_on_turn", "runtime.behaviours.", w.contract_on_turn);
    w.axle_placement = field(b, "axle_placement", "runtime.behaviours.", w.axle_placement);
  }
  driver::validate(s);
  return s;
}

}  // namespace marsokhod::runner
