#include "link/foxglove_protocol.hpp"

#include <limits>

#include "link/json_fields.hpp"

namespace marsokhod::link::foxglove {
namespace {

using Json = nlohmann::json;

void append_le(std::string& out, std::uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xFFU));
}

// A whole number in [0, 2³²): channel and subscription ids.
std::uint32_t read_id(const Json& value, const std::string& field) {
  const bool whole = value.is_number_unsigned() ||
                     (value.is_number_integer() && value.get<std::int64_t>() >= 0);
  if (!whole || value.get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max()) {
    throw FieldError(field, field + ": expected a whole number 0..4294967295, got " +
                                shown_value(value));
  }
  return static_cast<std::uint32_t>(value.get<std::uint64_t>());
}

const Json& require(const Json& object, const char* key) {
  const auto it = object.find(key);
  if (it == object.end()) throw FieldError(key, std::string(key) + ": missing");
  return *it;
}

const Json& read_array(const Json& object, const char* key) {
  const Json& value = require(object, key);
  if (!value.is_array()) {
    throw FieldError(key, std::string(key) + ": expected an array, got " + shown_value(value));
  }
  return value;
}

std::vector<std::string> read_names(const Json& object, const char* key) {
  std::vector<std::string> names;
  const Json& list = read_array(object, key);
  for (std::size_t i = 0; i < list.size(); ++i) {
    names.push_back(read_string(list[i], std::string(key) + "[" + std::to_string(i) + "]"));
  }
  return names;
}

std::optional<std::string> read_request_id(const Json& object) {
  const auto it = object.find("id");
  if (it == object.end()) return std::nullopt;
  return read_string(*it, "id");
}

ClientOp parse_op(const Json& message) {
  if (!message.is_object()) {
    throw FieldError("json", "expected a JSON object with an \"op\", got " + shown_value(message));
  }
  const std::string op = read_string(require(message, "op"), "op");
  if (op == "subscribe") {
    reject_unknown_keys(message, "", {"op", "subscriptions"}, "a subscribe");
    Subscribe out;
    const Json& list = read_array(message, "subscriptions");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string at = "subscriptions[" + std::to_string(i) + "]";
      if (!list[i].is_object()) throw FieldError(at, at + ": expected an object {id, channelId}");
      reject_unknown_keys(list[i], at + ".", {"id", "channelId"}, "a subscription");
      out.subscriptions.emplace_back(read_id(require(list[i], "id"), at + ".id"),
                                     read_id(require(list[i], "channelId"), at + ".channelId"));
    }
    return out;
  }
  if (op == "unsubscribe") {
    reject_unknown_keys(message, "", {"op", "subscriptionIds"}, "an unsubscribe");
    Unsubscribe out;
    const Json& list = read_array(message, "subscriptionIds");
    for (std::size_t i = 0; i < list.size(); ++i) {
      out.subscription_ids.push_back(read_id(list[i], "subscriptionIds[" + std::to_string(i) + "]"));
    }
    return out;
  }
  if (op == "getParameters") {
    reject_unknown_keys(message, "", {"op", "parameterNames", "id"}, "a getParameters");
    return GetParameters{read_names(message, "parameterNames"), read_request_id(message)};
  }
  if (op == "setParameters") {
    reject_unknown_keys(message, "", {"op", "parameters", "id"}, "a setParameters");
    return SetParameters{read_array(message, "parameters"), read_request_id(message)};
  }
  if (op == "subscribeParameterUpdates") {
    reject_unknown_keys(message, "", {"op", "parameterNames"}, "a subscribeParameterUpdates");
    return SubscribeParameterUpdates{read_names(message, "parameterNames")};
  }
  if (op == "unsubscribeParameterUpdates") {
    reject_unknown_keys(message, "", {"op", "parameterNames"}, "an unsubscribeParameterUpdates");
    return UnsubscribeParameterUpdates{read_names(message, "parameterNames")};
  }
  throw FieldError("op", "op: " + shown_value(message["op"]) +
                             " is not supported here; this server takes subscribe, unsubscribe, "
                             "getParameters, setParameters, subscribeParameterUpdates and "
                             "unsubscribeParameterUpdates (no clientPublish, services or assets)");
}

// The settings object's leaves under dotted names.
void flatten(const Json& object, const std::string& prefix, Json& out) {
  for (const auto& [key, value] : object.items()) {
    if (value.is_object()) {
      flatten(value, prefix + key + ".", out);
      continue;
    }
    Json parameter = {{"name", prefix + key}, {"value", value}};
    // Foxglove shows a number without a type as an integer when it happens to be whole.
    if (value.is_number()) parameter["type"] = "float64";
    out.push_back(std::move(parameter));
  }
}

}  // namespace

Json server_info_json(const std::string& name) {
  return {{"op", "serverInfo"},
          {"name", name},
          {"capabilities", {"time", "parameters", "parametersSubscribe"}},
          {"metadata",
           {{"time", "the rover's mission time (simulated time in the simulator)"},
            {"parameters", "the run-time settings; set only by the console holding control"}}}};
}

Json advertise_json(const std::vector<Channel>& channels) {
  Json list = Json::array();
  for (const Channel& c : channels) {
    list.push_back({{"id", c.id},
                    {"topic", c.topic},
                    {"encoding", "json"},
                    {"schemaName", c.schema_name},
                    {"schema", c.schema},
                    {"schemaEncoding", "jsonschema"}});
  }
  return {{"op", "advertise"}, {"channels", list}};
}

Json status_message(StatusLevel level, const std::string& message) {
  return {{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}};
}

Json parameter_values_json(const Json& parameters, const std::optional<std::string>& id) {
  Json out = {{"op", "parameterValues"}, {"parameters", parameters}};
  if (id) out["id"] = *id;
  return out;
}

std::string message_data(std::uint32_t subscription_id, std::uint64_t log_time_ns,
                         std::string_view payload) {
  std::string out;
  out.reserve(13 + payload.size());
  out.push_back(static_cast<char>(kMessageDataOpcode));
  append_le(out, subscription_id, 4);
  append_le(out, log_time_ns, 8);
  out.append(payload);
  return out;
}

std::string time_message(std::uint64_t time_ns) {
  std::string out(1, static_cast<char>(kTimeOpcode));
  append_le(out, time_ns, 8);
  return out;
}

ClientOp parse_client_op(std::string_view text) {
  if (text.size() > kMaxClientMessageBytes) {
    return FoxgloveError{"the message is " + std::to_string(text.size()) + " bytes; at most " +
                         std::to_string(kMaxClientMessageBytes)};
  }
  std::string op = "message";
  try {
    const Json message = parse_json_strictly(text);
    if (message.is_object() && message.contains("op") && message["op"].is_string()) {
      op = message["op"].get<std::string>();
    }
    return parse_op(message);
  } catch (const FieldError& error) {
    return FoxgloveError{(op == "message" ? "" : op + ": ") + error.what()};
  } catch (const std::exception& error) {
    return FoxgloveError{std::string("cannot read the message: ") + error.what()};
  }
}

Json settings_parameters(const Json& settings) {
  Json out = Json::array();
  if (settings.is_object()) flatten(settings, "", out);
  return out;
}

std::variant<ConfigureMessage, FoxgloveError> configure_of(const Json& parameters,
                                                           const Params& params) {
  Json configure = {{"type", "configure"}};
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    const Json& p = parameters[i];
    const std::string at = "parameters[" + std::to_string(i) + "]";
    if (!p.is_object() || !p.contains("name") || !p["name"].is_string() || !p.contains("value")) {
      return FoxgloveError{"setParameters: " + at + ": expected {\"name\": …, \"value\": …}"};
    }
    const std::string name = p["name"].get<std::string>();
    const auto dot = name.find('.');
    const std::string key = name.substr(0, dot);
    const bool leaf = dot == std::string::npos;
    // "type" is the configure message's own key, not a setting.
    if (key == "type" || (!leaf && configure.contains(key) && !configure[key].is_object()) ||
        (leaf && configure.contains(key))) {
      return FoxgloveError{"setParameters: " + at + ": " + field_name(name) +
                           " is not a setting, or appears twice"};
    }
    if (leaf) {
      configure[key] = p["value"];
      continue;
    }
    Json& group = configure[key];
    const std::string rest = name.substr(dot + 1);
    if (group.contains(rest)) {
      return FoxgloveError{"setParameters: " + at + ": " + field_name(name) + " appears twice"};
    }
    group[rest] = p["value"];
  }
  const ParseResult parsed = parse_operator_message(configure.dump(), params);
  if (const auto* error = std::get_if<MessageError>(&parsed)) {
    return FoxgloveError{"setParameters: " + error->message};
  }
  if (const auto* message = std::get_if<ConfigureMessage>(&parsed)) return *message;
  return FoxgloveError{"setParameters: not a setting"};
}

}  // namespace marsokhod::link::foxglove
