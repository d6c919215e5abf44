#include "link/command_json.hpp"

#include <array>
#include <utility>

#include "link/json_fields.hpp"

namespace marsokhod::link {
namespace {

using Json = nlohmann::json;

constexpr std::array<std::pair<LoadDistributionMode, std::string_view>, 3> kLoadDistributionIds = {{
    {LoadDistributionMode::kOff, "off"},
    {LoadDistributionMode::kVariance, "v"},
    {LoadDistributionMode::kSlip, "s"},
}};

constexpr std::array<std::pair<SupplyKind, std::string_view>, 2> kSupplyIds = {{
    {SupplyKind::kBattery, "battery"},
    {SupplyKind::kTether, "tether"},
}};

const std::vector<std::string_view> kBehaviourKeys = {"power_management", "slant_response",
                                                      "contract_on_turn", "axle_placement"};

std::string path(const Reading& how, std::string_view key) {
  return std::string(how.prefix) + std::string(key);
}

// Calls read(value) with the key's value when the object has the key.
template <typename Read>
void if_present(const Json& object, const char* key, Read&& read) {
  if (const auto it = object.find(key); it != object.end()) read(*it);
}

const Json& array_of(const Json& object, const char* key, std::size_t size, const char* items,
                     const Reading& how) {
  const std::string field = path(how, key);
  const auto it = object.find(key);
  if (it == object.end()) {
    throw FieldError(field, field + ": missing; " + std::string(how.what) +
                                " needs axes and buttons");
  }
  if (!it->is_array() || it->size() != size) {
    throw FieldError(field, field + ": expected an array of " + std::to_string(size) + " " +
                                items + " (W3C standard mapping), got " + shown_value(*it));
  }
  return *it;
}

mobility::Gait read_gait(const Json& value, const std::string& field) {
  const std::string& id = read_string(value, field);
  if (const auto gait = mobility::gait_from_id(id)) return *gait;
  std::string allowed;
  for (const mobility::Gait gait : mobility::kAllGaits) {
    allowed += (allowed.empty() ? "" : ", ") + std::string(mobility::gait_id(gait));
  }
  throw FieldError(field, field + ": unknown gait " + shown_value(value) + "; expected one of " +
                              allowed);
}

LoadDistributionMode read_load_distribution(const Json& value, const std::string& field) {
  const std::string& id = read_string(value, field);
  for (const auto& [mode, name] : kLoadDistributionIds) {
    if (id == name) return mode;
  }
  throw FieldError(field, field + ": unknown mode " + shown_value(value) +
                              "; expected \"off\", \"v\" (6.5) or \"s\" (6.6)");
}

// The recording's joint_buttons: [LB, LT, RB, RT] (contract and extend front, then rear).
mobility::JointButtons read_joint_buttons(const Json& value, const std::string& field) {
  if (!value.is_array() || value.size() != 4) {
    throw FieldError(field, field + ": expected an array of 4 booleans (LB, LT, RB, RT), got " +
                                shown_value(value));
  }
  std::array<bool, 4> b{};
  for (std::size_t i = 0; i < b.size(); ++i) {
    b[i] = read_bool(value[i], field + "[" + std::to_string(i) + "]");
  }
  return {b[0], b[1], b[2], b[3]};
}

void read_behaviours(const Json& value, const Reading& how, driver::SettingsChange& change) {
  const std::string field = path(how, "behaviours");
  if (!value.is_object()) {
    throw FieldError(field, field + ": expected an object of booleans, got " + shown_value(value));
  }
  reject_unknown_keys(value, field + ".", kBehaviourKeys, "behaviours");
  const auto flag = [&](const char* key, std::optional<bool>& target) {
    if_present(value, key, [&](const Json& v) { target = read_bool(v, field + "." + key); });
  };
  flag("power_management", change.power_management);
  flag("slant_response", change.slant_response);
  flag("contract_on_turn", change.contract_on_turn);
  flag("axle_placement", change.axle_placement);
}

}  // namespace

std::vector<std::string_view> gamepad_keys() { return {"axes", "buttons"}; }

mobility::GamepadState read_gamepad(const Json& object, const Reading& how) {
  mobility::GamepadState pad;
  const Json& axes = array_of(object, "axes", pad.axes.size(), "numbers in \u22121..1", how);
  const Json& buttons = array_of(object, "buttons", pad.buttons.size(), "booleans", how);
  for (std::size_t i = 0; i < pad.axes.size(); ++i) {
    pad.axes[i] = read_number(axes[i], path(how, "axes[" + std::to_string(i) + "]"));
  }
  for (std::size_t i = 0; i < pad.buttons.size(); ++i) {
    pad.buttons[i] = read_bool(buttons[i], path(how, "buttons[" + std::to_string(i) + "]"));
  }
  if (how.ranges != nullptr) {
    if (auto error = driver::check_gamepad(pad)) throw_field_error(*error, how.prefix);
  }
  return pad;
}

void write_gamepad(const mobility::GamepadState& gamepad, Json& object) {
  object["axes"] = gamepad.axes;
  object["buttons"] = gamepad.buttons;
}

std::vector<std::string_view> target_keys(TargetKeys keys) {
  std::vector<std::string_view> all = {"v1", "v2",   "v3",         "v4",
                                       "v6", "v7",   "gait",       "gait_speed",
                                       "calibration_mode"};
  if (keys == TargetKeys::kRecording) {
    all.insert(all.end(), {"joint_buttons", "front_joint_target", "rear_joint_target"});
  }
  return all;
}

mobility::OperatorTargets read_targets(const Json& object, TargetKeys keys, const Reading& how) {
  mobility::OperatorTargets t;
  const auto number = [&](const char* key, double& target) {
    if_present(object, key, [&](const Json& v) { target = read_number(v, path(how, key)); });
  };
  number("v1", t.v1_radps);
  number("v2", t.v2_radps);
  number("v3", t.v3_radps);
  number("v4", t.v4_radps);
  number("v6", t.v6_radps);
  number("v7", t.v7_radps);
  if_present(object, "gait", [&](const Json& v) { t.gait = read_gait(v, path(how, "gait")); });
  number("gait_speed", t.gait_speed);
  if_present(object, "calibration_mode", [&](const Json& v) {
    t.calibration_mode = read_bool(v, path(how, "calibration_mode"));
  });
  if (keys == TargetKeys::kRecording) {
    if_present(object, "joint_buttons", [&](const Json& v) {
      t.joint_buttons = read_joint_buttons(v, path(how, "joint_buttons"));
    });
    const auto joint = [&](const char* key, std::optional<double>& target) {
      if_present(object, key, [&](const Json& v) { target = read_number(v, path(how, key)); });
    };
    joint("front_joint_target", t.front_joint_target_rad);
    joint("rear_joint_target", t.rear_joint_target_rad);
  }
  if (how.ranges != nullptr) {
    if (auto error = driver::check_targets(t, *how.ranges)) throw_field_error(*error, how.prefix);
  }
  return t;
}

void write_targets(const mobility::OperatorTargets& t, TargetKeys keys, Json& object) {
  object["v1"] = t.v1_radps;
  object["v2"] = t.v2_radps;
  object["v3"] = t.v3_radps;
  object["v4"] = t.v4_radps;
  object["v6"] = t.v6_radps;
  object["v7"] = t.v7_radps;
  object["gait"] = mobility::gait_id(t.gait);
  object["gait_speed"] = t.gait_speed;
  object["calibration_mode"] = t.calibration_mode;
  if (keys == TargetKeys::kConsole) return;
  const mobility::JointButtons& b = t.joint_buttons;
  object["joint_buttons"] = {b.contract_front, b.extend_front, b.contract_rear, b.extend_rear};
  if (t.front_joint_target_rad) object["front_joint_target"] = *t.front_joint_target_rad;
  if (t.rear_joint_target_rad) object["rear_joint_target"] = *t.rear_joint_target_rad;
}

std::vector<std::string_view> velocity_keys() { return {"v_mps", "yaw_radps"}; }

navigation::VelocityCommand read_velocity(const Json& object, const Reading& how) {
  navigation::VelocityCommand c;
  const auto required = [&](const char* key, double& target) {
    const std::string field = path(how, key);
    const auto it = object.find(key);
    if (it == object.end()) {
      throw FieldError(field, field + ": missing; " + std::string(how.what) +
                                  " carries v_mps (forward, m/s) and yaw_radps (counter-clockwise)");
    }
    target = read_number(*it, field);
  };
  required("v_mps", c.v_mps);
  required("yaw_radps", c.yaw_radps);
  if (how.ranges != nullptr) {
    if (auto error = navigation::check_velocity(c, *how.ranges)) {
      throw FieldError(path(how, error->field), std::string(how.prefix) + error->message);
    }
  }
  return c;
}

void write_velocity(const navigation::VelocityCommand& c, Json& object) {
  object["v_mps"] = c.v_mps;
  object["yaw_radps"] = c.yaw_radps;
}

std::vector<std::string_view> mission_keys() {
  return {"kind", "angle_rad", "distance_m", "waypoints", "settle_s"};
}

navigation::MissionRequest read_mission(const Json& object, const Reading& how) {
  navigation::MissionRequest r;
  const std::string kind_field = path(how, "kind");
  const auto kind_it = object.find("kind");
  if (kind_it == object.end()) {
    throw FieldError(kind_field, kind_field + ": missing; a mission is \"turn\", \"move\" or \"goto\"");
  }
  const std::string& kind = read_string(*kind_it, kind_field);
  const char* needed = nullptr;
  if (kind == "turn") {
    r.kind = navigation::MissionKind::kTurn;
    needed = "angle_rad";
  } else if (kind == "move") {
    r.kind = navigation::MissionKind::kMove;
    needed = "distance_m";
  } else if (kind == "goto") {
    r.kind = navigation::MissionKind::kGoto;
    needed = "waypoints";
  } else {
    throw FieldError(kind_field, kind_field + ": unknown mission " + shown_value(*kind_it) +
                                     "; expected \"turn\", \"move\" or \"goto\"");
  }
  for (const char* key : {"angle_rad", "distance_m", "waypoints"}) {
    const bool present = object.contains(key);
    const std::string field = path(how, key);
    if (std::string_view(key) == needed && !present) {
      throw FieldError(field, field + ": missing; a " + kind + " mission needs it");
    }
    if (std::string_view(key) != needed && present) {
      throw FieldError(field, field + ": not a key of a " + kind + " mission (it takes " +
                                  needed + ")");
    }
  }
  if (r.kind == navigation::MissionKind::kTurn) {
    r.angle_rad = read_number(object.at("angle_rad"), path(how, "angle_rad"));
  } else if (r.kind == navigation::MissionKind::kMove) {
    r.distance_m = read_number(object.at("distance_m"), path(how, "distance_m"));
  } else {
    const Json& list = object.at("waypoints");
    const std::string field = path(how, "waypoints");
    if (!list.is_array()) {
      throw FieldError(field, field + ": expected an array of {\"x_m\":…,\"y_m\":…}, got " +
                                  shown_value(list));
    }
    if (list.size() > navigation::kMaxWaypoints) {
      throw FieldError(field, field + ": " + std::to_string(list.size()) +
                                  " waypoints; at most " +
                                  std::to_string(navigation::kMaxWaypoints));
    }
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string at = field + "[" + std::to_string(i) + "]";
      const Json& w = list[i];
      if (!w.is_object()) {
        throw FieldError(at, at + ": expected {\"x_m\":…,\"y_m\":…}, got " + shown_value(w));
      }
      reject_unknown_keys(w, at + ".", {"x_m", "y_m"}, "a waypoint");
      for (const char* key : {"x_m", "y_m"}) {
        if (!w.contains(key)) throw FieldError(at + "." + key, at + "." + key + ": missing");
      }
      r.waypoints.push_back({read_number(w.at("x_m"), at + ".x_m"),
                             read_number(w.at("y_m"), at + ".y_m")});
    }
  }
  if (const auto it = object.find("settle_s"); it != object.end()) {
    r.settle_s = read_number(*it, path(how, "settle_s"));
  }
  if (auto error = navigation::check_request(r)) {
    throw FieldError(path(how, error->field), std::string(how.prefix) + error->message);
  }
  return r;
}

void write_mission(const navigation::MissionRequest& r, Json& object) {
  object["kind"] = navigation::mission_kind_id(r.kind);
  switch (r.kind) {
    case navigation::MissionKind::kTurn:
      object["angle_rad"] = r.angle_rad;
      break;
    case navigation::MissionKind::kMove:
      object["distance_m"] = r.distance_m;
      break;
    case navigation::MissionKind::kGoto: {
      Json list = Json::array();
      for (const navigation::Waypoint& w : r.waypoints) list.push_back({{"x_m", w.x_m}, {"y_m", w.y_m}});
      object["waypoints"] = list;
      break;
    }
    case navigation::MissionKind::kNone:
    case navigation::MissionKind::kVelocity:
      break;
  }
  if (r.settle_s) object["settle_s"] = *r.settle_s;
}

std::vector<std::string_view> settings_keys() {
  return {"max_drop_v", "load_distribution", "behaviours", "speed_scale", "supply"};
}

driver::SettingsChange read_settings_change(const Json& object, const Reading& how) {
  driver::SettingsChange change;
  if_present(object, "max_drop_v",
             [&](const Json& v) { change.max_drop_v = read_number(v, path(how, "max_drop_v")); });
  if_present(object, "load_distribution", [&](const Json& v) {
    change.load_distribution = read_load_distribution(v, path(how, "load_distribution"));
  });
  if_present(object, "behaviours", [&](const Json& v) { read_behaviours(v, how, change); });
  if_present(object, "speed_scale", [&](const Json& v) {
    change.speed_scale = read_number(v, path(how, "speed_scale"));
  });
  if_present(object, "supply", [&](const Json& v) {
    const std::string field = path(how, "supply");
    const std::string& id = read_string(v, field);
    for (const auto& [kind, name] : kSupplyIds) {
      if (id == name) change.supply = kind;
    }
    if (!change.supply) {
      throw FieldError(field, field + ": unknown supply " + shown_value(v) +
                                  "; expected \"battery\" or \"tether\"");
    }
  });
  if (auto error = driver::check_settings(change)) throw_field_error(*error, how.prefix);
  return change;
}

void write_settings_change(const driver::SettingsChange& change, Json& object) {
  if (change.max_drop_v) object["max_drop_v"] = *change.max_drop_v;
  if (change.load_distribution) {
    object["load_distribution"] = load_distribution_id(*change.load_distribution);
  }
  Json behaviours = Json::object();
  const auto flag = [&behaviours](const char* key, const std::optional<bool>& value) {
    if (value) behaviours[key] = *value;
  };
  flag("power_management", change.power_management);
  flag("slant_response", change.slant_response);
  flag("contract_on_turn", change.contract_on_turn);
  flag("axle_placement", change.axle_placement);
  if (!behaviours.empty()) object["behaviours"] = behaviours;
  if (change.speed_scale) object["speed_scale"] = *change.speed_scale;
  if (change.supply) {
    for (const auto& [kind, name] : kSupplyIds) {
      if (kind == *change.supply) object["supply"] = name;
    }
  }
}

Json operator_input_json(const driver::OperatorInput& input) {
  Json j = Json::object();
  if (input.gamepad) write_gamepad(*input.gamepad, j["gamepad"]);
  if (input.targets) write_targets(*input.targets, TargetKeys::kRecording, j["targets"]);
  if (input.velocity) write_velocity(*input.velocity, j["velocity"]);
  if (input.mission) write_mission(*input.mission, j["mission"]);
  if (input.heartbeat) j["heartbeat"] = true;
  if (input.stop) j["stop"] = true;
  if (!input.stop_reason.empty()) j["stop_reason"] = input.stop_reason;
  if (input.clear_faults) j["clear_faults"] = true;
  return j;
}

driver::OperatorInput operator_input_from_json(const Json& j) {
  if (!j.is_object()) throw FieldError("input", "input: expected an object, got " + shown_value(j));
  reject_unknown_keys(j, "input.",
                      {"gamepad", "targets", "velocity", "mission", "heartbeat", "stop",
                       "stop_reason", "clear_faults"},
                      "an operator input");
  driver::OperatorInput in;
  if_present(j, "gamepad", [&](const Json& g) {
    if (!g.is_object()) throw FieldError("gamepad", "gamepad: expected an object");
    reject_unknown_keys(g, "gamepad.", gamepad_keys(), "gamepad");
    in.gamepad = read_gamepad(g, {"gamepad.", "gamepad", nullptr});
  });
  if_present(j, "targets", [&](const Json& t) {
    if (!t.is_object()) throw FieldError("targets", "targets: expected an object");
    reject_unknown_keys(t, "targets.", target_keys(TargetKeys::kRecording), "targets");
    in.targets = read_targets(t, TargetKeys::kRecording, {"targets.", "targets", nullptr});
  });
  if_present(j, "velocity", [&](const Json& v) {
    if (!v.is_object()) throw FieldError("velocity", "velocity: expected an object");
    reject_unknown_keys(v, "velocity.", velocity_keys(), "velocity");
    in.velocity = read_velocity(v, {"velocity.", "velocity", nullptr});
  });
  if_present(j, "mission", [&](const Json& m) {
    if (!m.is_object()) throw FieldError("mission", "mission: expected an object");
    reject_unknown_keys(m, "mission.", mission_keys(), "mission");
    in.mission = read_mission(m, {"mission.", "mission", nullptr});
  });
  if_present(j, "heartbeat",
             [&](const Json& v) { in.heartbeat = read_bool(v, "input.heartbeat"); });
  if_present(j, "stop", [&](const Json& v) { in.stop = read_bool(v, "input.stop"); });
  if_present(j, "stop_reason",
             [&](const Json& v) { in.stop_reason = read_string(v, "input.stop_reason"); });
  if_present(j, "clear_faults",
             [&](const Json& v) { in.clear_faults = read_bool(v, "input.clear_faults"); });
  return in;
}

Json runtime_settings_json(const driver::RuntimeSettings& settings) {
  Json j = Json::object();
  write_settings_change(driver::SettingsChange::all_of(settings), j);
  return j;
}

driver::RuntimeSettings runtime_settings_from_json(const Json& j,
                                                   const driver::RuntimeSettings& base) {
  if (!j.is_object()) throw FieldError("runtime", "runtime: expected an object");
  reject_unknown_keys(j, "runtime.", settings_keys(), "runtime");
  return read_settings_change(j, {"runtime.", "runtime", nullptr}).applied_to(base);
}

std::string_view load_distribution_id(LoadDistributionMode mode) {
  for (const auto& [value, id] : kLoadDistributionIds) {
    if (value == mode) return id;
  }
  return "off";
}

}  // namespace marsokhod::link
