#include "link/operator_message.hpp"

#include <type_traits>
#include <utility>

#include "link/command_json.hpp"
#include "link/json_fields.hpp"

namespace marsokhod::link {
namespace {

using Json = nlohmann::json;

// In the order of the OperatorMessage alternatives (message_type indexes it).
constexpr std::array<std::string_view, std::variant_size_v<OperatorMessage>> kTypeNames = {
    "gamepad", "targets", "stop", "clear_faults", "take_control", "release_control", "configure",
    "ping", "velocity", "mission", "heartbeat"};

// 2^53 − 1: the largest integer a JavaScript number (the console's) holds exactly.
constexpr double kMaxSeq = 9007199254740991.0;
constexpr double kMaxSentMs = 1e15;  // year 33658 since 1970: any clock's milliseconds fit

// The message's keys: its type, the stamp when it has one, and the command's own.
std::vector<std::string_view> message_keys(bool stamped, std::vector<std::string_view> keys) {
  std::vector<std::string_view> all = {"type"};
  if (stamped) all.insert(all.end(), {"seq", "sent_ms"});
  all.insert(all.end(), keys.begin(), keys.end());
  return all;
}

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

GamepadMessage parse_gamepad(const Json& message, const Params& params) {
  constexpr const char* kWhat = "a gamepad message";
  reject_unknown_keys(message, "", message_keys(true, gamepad_keys()), kWhat);
  GamepadMessage gamepad;
  gamepad.stamp = read_stamp(message, kWhat);
  gamepad.reading = read_gamepad(message, {"", kWhat, &params});
  return gamepad;
}

TargetsMessage parse_targets(const Json& message, const Params& params) {
  constexpr const char* kWhat = "a targets message";
  reject_unknown_keys(message, "", message_keys(true, target_keys(TargetKeys::kConsole)), kWhat);
  TargetsMessage targets;
  targets.stamp = read_stamp(message, kWhat);
  targets.targets = read_targets(message, TargetKeys::kConsole, {"", kWhat, &params});
  return targets;
}

VelocityMessage parse_velocity(const Json& message, const Params& params) {
  constexpr const char* kWhat = "a velocity message";
  reject_unknown_keys(message, "", message_keys(true, velocity_keys()), kWhat);
  VelocityMessage velocity;
  velocity.stamp = read_stamp(message, kWhat);
  velocity.command = read_velocity(message, {"", kWhat, &params});
  return velocity;
}

MissionMessage parse_mission(const Json& message) {
  constexpr const char* kWhat = "a mission message";
  reject_unknown_keys(message, "", message_keys(true, mission_keys()), kWhat);
  MissionMessage mission;
  mission.stamp = read_stamp(message, kWhat);
  mission.request = read_mission(message, {"", kWhat, nullptr});
  return mission;
}

HeartbeatMessage parse_heartbeat(const Json& message) {
  constexpr const char* kWhat = "a heartbeat message";
  reject_unknown_keys(message, "", message_keys(true, {}), kWhat);
  return {read_stamp(message, kWhat)};
}

ConfigureMessage parse_configure(const Json& message) {
  constexpr const char* kWhat = "a configure message";
  reject_unknown_keys(message, "", message_keys(false, settings_keys()), kWhat);
  return {read_settings_change(message, {"", kWhat, nullptr})};
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
  if (type == "gamepad") return parse_gamepad(message, params);
  if (type == "targets") return parse_targets(message, params);
  if (type == "configure") return parse_configure(message);
  if (type == "velocity") return parse_velocity(message, params);
  if (type == "mission") return parse_mission(message);
  if (type == "heartbeat") return parse_heartbeat(message);
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

Json operator_message_json(const OperatorMessage& message) {
  Json out = {{"type", message_type(message)}};
  if (const auto stamp = input_stamp(message)) {
    out["seq"] = stamp->seq;
    out["sent_ms"] = stamp->sent_ms;
  }
  if (const auto* gamepad = std::get_if<GamepadMessage>(&message)) {
    write_gamepad(gamepad->reading, out);
  } else if (const auto* targets = std::get_if<TargetsMessage>(&message)) {
    write_targets(targets->targets, TargetKeys::kConsole, out);
  } else if (const auto* configure = std::get_if<ConfigureMessage>(&message)) {
    write_settings_change(configure->change, out);
  } else if (const auto* velocity = std::get_if<VelocityMessage>(&message)) {
    write_velocity(velocity->command, out);
  } else if (const auto* mission = std::get_if<MissionMessage>(&message)) {
    write_mission(mission->request, out);
  }
  return out;
}

std::optional<driver::OperatorInput> operator_input(const OperatorMessage& message) {
  driver::OperatorInput input;
  if (const auto* gamepad = std::get_if<GamepadMessage>(&message)) {
    input.gamepad = gamepad->reading;
  } else if (const auto* targets = std::get_if<TargetsMessage>(&message)) {
    input.targets = targets->targets;
  } else if (const auto* velocity = std::get_if<VelocityMessage>(&message)) {
    input.velocity = velocity->command;
  } else if (const auto* mission = std::get_if<MissionMessage>(&message)) {
    input.mission = mission->request;
  } else if (std::holds_alternative<HeartbeatMessage>(message)) {
    input.heartbeat = true;
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
  if (const auto* velocity = std::get_if<VelocityMessage>(&message)) return velocity->stamp;
  if (const auto* mission = std::get_if<MissionMessage>(&message)) return mission->stamp;
  if (const auto* heartbeat = std::get_if<HeartbeatMessage>(&message)) return heartbeat->stamp;
  return std::nullopt;
}

}  // namespace marsokhod::link
