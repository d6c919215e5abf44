#include "link/operator_message.hpp"

#include <type_traits>
#include <utility>

#include "link/json_fields.hpp"

namespace marsokhod::link {
namespace {

using Json = nlohmann::json;

// In the order of the OperatorMessage alternatives (message_type indexes it).
constexpr std::array<std::string_view, std::variant_size_v<OperatorMessage>> kTypeNames = {
    "gamepad", "targets", "stop", "clear_faults", "take_control", "release_control", "configure",
    "ping"};

constexpr std::array<std::pair<LoadDistributionMode, std::string_view>, 3> kLoadDistributionIds = {{
    {LoadDistributionMode::kOff, "off"},
    {LoadDistributionMode::kVariance, "v"},
    {LoadDistributionMode::kSlip, "s"},
}};

const Json& array_of(const Json& message, const char* key, std::size_t size, const char* what) {
  const auto it = message.find(key);
  if (it == message.end()) {
    throw FieldError(key, std::string(key) + ": missing; a gamepad message needs axes and buttons");
  }
  if (!it->is_array() || it->size() != size) {
    throw FieldError(key, std::string(key) + ": expected an array of " + std::to_string(size) +
                              " " + what + " (W3C standard mapping), got " + shown_value(*it));
  }
  return *it;
}

// 2^53 − 1: the largest integer a JavaScript number (the console's) holds exactly.
constexpr double kMaxSeq = 9007199254740991.0;
constexpr double kMaxSentMs = 1e15;  // year 33658 since 1970: any clock's milliseconds fit

InputStamp read_stamp(const Json& message, const char* what) {
  InputStamp stamp;
  for (const char* key : {"seq", "sent_ms"}) {
    if (!message.contains(key)) {
      throw FieldError(key, std::string(key) + ": missing; " + what +
                                " carries seq (counting up from 1) and sent_ms (the console's "
                                "clock in ms)");
    }
  }
  const double seq = read_number(message.at("seq"), "seq", {0.0, kMaxSeq, false, ""});
  if (seq != static_cast<double>(static_cast<std::uint64_t>(seq))) {
    throw FieldError("seq", "seq: expected an integer, got " + shown_value(message.at("seq")));
  }
  stamp.seq = static_cast<std::uint64_t>(seq);
  stamp.sent_ms = read_number(message.at("sent_ms"), "sent_ms", {0.0, kMaxSentMs, false, "ms"});
  return stamp;
}

GamepadMessage parse_gamepad(const Json& message) {
  reject_unknown_keys(message, "", {"type", "seq", "sent_ms", "axes", "buttons"},
                      "a gamepad message");
  GamepadMessage gamepad;
  gamepad.stamp = read_stamp(message, "a gamepad message");
  const Json& axes = array_of(message, "axes", gamepad.axes.size(), "numbers in \u22121..1");
  const Json& buttons = array_of(message, "buttons", gamepad.buttons.size(), "booleans");
  for (std::size_t i = 0; i < gamepad.axes.size(); ++i) {
    gamepad.axes[i] = read_number(axes[i], "axes[" + std::to_string(i) + "]",
                                  symmetric_range(1.0, ""));
  }
  for (std::size_t i = 0; i < gamepad.buttons.size(); ++i) {
    gamepad.buttons[i] = read_bool(buttons[i], "buttons[" + std::to_string(i) + "]");
  }
  return gamepad;
}

mobility::Gait read_gait(const Json& value) {
  const std::string& id = read_string(value, "gait");
  if (const auto gait = mobility::gait_from_id(id)) return *gait;
  std::string allowed;
  for (const mobility::Gait gait : mobility::kAllGaits) {
    allowed += (allowed.empty() ? "" : ", ") + std::string(mobility::gait_id(gait));
  }
  throw FieldError("gait", "gait: unknown gait " + shown_value(value) + "; expected one of " + allowed);
}

TargetsMessage parse_targets(const Json& message, const Params& params) {
  reject_unknown_keys(message, "",
                      {"type", "seq", "sent_ms", "v1", "v2", "v4", "v6", "v7", "gait",
                       "gait_speed", "calibration_mode"},
                      "a targets message");
  const OperatorParams& limits = params.operator_input;
  const double joint_limit = params.motors.max_no_load_speed_radps;
  TargetsMessage targets;
  targets.stamp = read_stamp(message, "a targets message");
  const auto speed = [&message](const char* key, double limit, double& out) {
    if (const auto it = message.find(key); it != message.end()) {
      out = read_number(*it, key, symmetric_range(limit, "rad/s"));
    }
  };
  speed("v1", limits.max_drive_speed_radps, targets.v1_radps);
  speed("v2", limits.max_spin_speed_radps, targets.v2_radps);
  speed("v4", limits.max_trench_speed_radps, targets.v4_radps);
  speed("v6", joint_limit, targets.v6_radps);
  speed("v7", joint_limit, targets.v7_radps);
  if (const auto it = message.find("gait"); it != message.end()) targets.gait = read_gait(*it);
  if (const auto it = message.find("gait_speed"); it != message.end()) {
    targets.gait_speed = read_number(*it, "gait_speed", symmetric_range(1.0, ""));
  }
  if (const auto it = message.find("calibration_mode"); it != message.end()) {
    targets.calibration_mode = read_bool(*it, "calibration_mode");
  }
  return targets;
}

LoadDistributionMode read_load_distribution(const Json& value) {
  const std::string& id = read_string(value, "load_distribution");
  for (const auto& [mode, name] : kLoadDistributionIds) {
    if (id == name) return mode;
  }
  throw FieldError("load_distribution", "load_distribution: unknown mode " + shown_value(value) +
                                            "; expected \"off\", \"v\" (6.5) or \"s\" (6.6)");
}

void parse_behaviours(const Json& value, ConfigureMessage& out) {
  if (!value.is_object()) {
    throw FieldError("behaviours", "behaviours: expected an object of booleans, got " +
                                       shown_value(value));
  }
  reject_unknown_keys(value, "behaviours.",
                      {"power_management", "slant_response", "contract_on_turn", "axle_placement"},
                      "behaviours");
  const auto flag = [&value](const char* key, std::optional<bool>& target) {
    if (const auto it = value.find(key); it != value.end()) {
      target = read_bool(*it, "behaviours." + std::string(key));
    }
  };
  flag("power_management", out.power_management);
  flag("slant_response", out.slant_response);
  flag("contract_on_turn", out.contract_on_turn);
  flag("axle_placement", out.axle_placement);
}

ConfigureMessage parse_configure(const Json& message) {
  reject_unknown_keys(message, "",
                      {"type", "max_drop_v", "load_distribution", "behaviours", "speed_scale"},
                      "a configure message");
  ConfigureMessage configure;
  if (const auto it = message.find("max_drop_v"); it != message.end()) {
    configure.max_drop_v = read_number(*it, "max_drop_v", {0.0, 10.0, true, "V"});
  }
  if (const auto it = message.find("load_distribution"); it != message.end()) {
    configure.load_distribution = read_load_distribution(*it);
  }
  if (const auto it = message.find("behaviours"); it != message.end()) {
    parse_behaviours(*it, configure);
  }
  if (const auto it = message.find("speed_scale"); it != message.end()) {
    configure.speed_scale = read_number(*it, "speed_scale", {0.0, 1.0, false, ""});
  }
  return configure;
}

template <typename Message>
Message parse_bare(const Json& message, std::string_view type) {
  reject_unknown_keys(message, "", {"type"}, "a " + std::string(type) + " message");
  return Message{};
}

ParseResult parse_object(const Json& message, const Params& params) {
  if (!message.is_object()) {
    throw FieldError("json", "expected a JSON object such as {\"type\":\"ping\"}, got " +
                                 shown_value(message));
  }
  const auto type_it = message.find("type");
  if (type_it == message.end()) throw FieldError("type", "type: missing; every message has one");
  const std::string& type = read_string(*type_it, "type");
  if (type == "gamepad") return parse_gamepad(message);
  if (type == "targets") return parse_targets(message, params);
  if (type == "configure") return parse_configure(message);
  if (type == "stop") return parse_bare<StopMessage>(message, type);
  if (type == "clear_faults") return parse_bare<ClearFaultsMessage>(message, type);
  if (type == "take_control") return parse_bare<TakeControlMessage>(message, type);
  if (type == "release_control") return parse_bare<ReleaseControlMessage>(message, type);
  if (type == "ping") return parse_bare<PingMessage>(message, type);
  std::string allowed;
  for (std::string_view name : kTypeNames) allowed += (allowed.empty() ? "" : ", ") + std::string(name);
  throw FieldError("type", "type: unknown message type " + shown_value(*type_it) +
                               "; expected one of " + allowed);
}

}  // namespace

ParseResult parse_operator_message(std::string_view json, const Params& params) {
  if (json.size() > kMaxOperatorMessageBytes) {
    return MessageError{"json", "the message is " + std::to_string(json.size()) +
                                    " bytes; at most " + std::to_string(kMaxOperatorMessageBytes)};
  }
  try {
    return parse_object(parse_json_strictly(json), params);
  } catch (const FieldError& error) {
    return MessageError{error.field(), error.what()};
  } catch (const std::exception& error) {
    // Not expected (every read checks the type first); kept so that the parser never throws.
    return MessageError{"json", std::string("cannot read the message: ") + error.what()};
  }
}

std::optional<OperatorMessage> message_of(const ParseResult& result) {
  return std::visit(
      [](const auto& value) -> std::optional<OperatorMessage> {
        if constexpr (std::is_same_v<std::decay_t<decltype(value)>, MessageError>) {
          return std::nullopt;
        } else {
          return OperatorMessage(value);
        }
      },
      result);
}

std::string_view message_type(const OperatorMessage& message) {
  return kTypeNames.at(message.index());
}

std::string_view load_distribution_id(LoadDistributionMode mode) {
  for (const auto& [value, id] : kLoadDistributionIds) {
    if (value == mode) return id;
  }
  return "off";
}

namespace {

Json configure_json(const ConfigureMessage& configure) {
  Json out = {{"type", "configure"}};
  if (configure.max_drop_v) out["max_drop_v"] = *configure.max_drop_v;
  if (configure.load_distribution) {
    out["load_distribution"] = load_distribution_id(*configure.load_distribution);
  }
  Json behaviours = Json::object();
  const auto flag = [&behaviours](const char* key, const std::optional<bool>& value) {
    if (value) behaviours[key] = *value;
  };
  flag("power_management", configure.power_management);
  flag("slant_response", configure.slant_response);
  flag("contract_on_turn", configure.contract_on_turn);
  flag("axle_placement", configure.axle_placement);
  if (!behaviours.empty()) out["behaviours"] = behaviours;
  if (configure.speed_scale) out["speed_scale"] = *configure.speed_scale;
  return out;
}

}  // namespace

Json operator_message_json(const OperatorMessage& message) {
  return std::visit(
      [&message](const auto& value) -> Json {
        using Message = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<Message, GamepadMessage>) {
          return {{"type", "gamepad"},
                  {"seq", value.stamp.seq},
                  {"sent_ms", value.stamp.sent_ms},
                  {"axes", value.axes},
                  {"buttons", value.buttons}};
        } else if constexpr (std::is_same_v<Message, TargetsMessage>) {
          return {{"type", "targets"},          {"seq", value.stamp.seq},
                  {"sent_ms", value.stamp.sent_ms},
                  {"v1", value.v1_radps},
                  {"v2", value.v2_radps},       {"v4", value.v4_radps},
                  {"v6", value.v6_radps},       {"v7", value.v7_radps},
                  {"gait", mobility::gait_id(value.gait)}, {"gait_speed", value.gait_speed},
                  {"calibration_mode", value.calibration_mode}};
        } else if constexpr (std::is_same_v<Message, ConfigureMessage>) {
          return configure_json(value);
        } else {
          return {{"type", message_type(message)}};
        }
      },
      message);
}

std::optional<driver::OperatorInput> operator_input(const OperatorMessage& message) {
  driver::OperatorInput input;
  if (const auto* gamepad = std::get_if<GamepadMessage>(&message)) {
    input.gamepad = mobility::GamepadState{gamepad->axes, gamepad->buttons};
  } else if (const auto* t = std::get_if<TargetsMessage>(&message)) {
    mobility::OperatorTargets targets;
    targets.v1_radps = t->v1_radps;
    targets.v2_radps = t->v2_radps;
    targets.v4_radps = t->v4_radps;
    targets.v6_radps = t->v6_radps;
    targets.v7_radps = t->v7_radps;
    targets.gait = t->gait;
    targets.gait_speed = t->gait_speed;
    targets.calibration_mode = t->calibration_mode;
    input.targets = targets;
  } else if (std::holds_alternative<StopMessage>(message)) {
    input.stop = true;
  } else if (std::holds_alternative<ClearFaultsMessage>(message)) {
    input.clear_faults = true;
  } else {
    return std::nullopt;
  }
  return input;
}

std::optional<InputStamp> input_stamp(const OperatorMessage& message) {
  if (const auto* gamepad = std::get_if<GamepadMessage>(&message)) return gamepad->stamp;
  if (const auto* targets = std::get_if<TargetsMessage>(&message)) return targets->stamp;
  return std::nullopt;
}

driver::RuntimeSettings apply_configuration(const ConfigureMessage& message,
                                            driver::RuntimeSettings current) {
  if (message.max_drop_v) current.max_drop_v = *message.max_drop_v;
  if (message.speed_scale) current.speed_scale = *message.speed_scale;
  if (message.load_distribution) current.switches.load_distribution = *message.load_distribution;
  if (message.power_management) current.switches.power_management = *message.power_management;
  if (message.slant_response) current.switches.slant_response = *message.slant_response;
  if (message.contract_on_turn) current.switches.contract_on_turn = *message.contract_on_turn;
  if (message.axle_placement) current.switches.axle_placement = *message.axle_placement;
  return current;
}

}  // namespace marsokhod::link
