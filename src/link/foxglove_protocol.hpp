// Foxglove's WebSocket protocol (subprotocol foxglove.websocket.v1, the spec in the
// foxglove/ws-protocol repository on GitHub), the part the link server speaks on /foxglove
// (docs/foxglove.md): the server's JSON messages (serverInfo, status, advertise, parameterValues),
// its binary ones (message data, opcode 0x01; time, 0x02), and the client's operations it takes
// (subscribe, unsubscribe, getParameters, setParameters, subscribeParameterUpdates,
// unsubscribeParameterUpdates), parsed strictly: anything else is a FoxgloveError whose message
// the server sends back as a status. The run-time settings (driver::RuntimeSettings, the
// console's `configure`) are the Foxglove parameters, named by configure's keys with a dot into
// `behaviours` ("max_drop_v", "behaviours.slant_response"). Pure: no I/O.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/params.hpp"
#include "driver/operator_commands.hpp"
#include "link/operator_message.hpp"

namespace marsokhod::link::foxglove {

inline constexpr std::string_view kSubprotocol = "foxglove.websocket.v1";
inline constexpr std::uint8_t kMessageDataOpcode = 0x01;
inline constexpr std::uint8_t kTimeOpcode = 0x02;
// A client's text message is small (a subscribe of every channel is well below this).
inline constexpr std::size_t kMaxClientMessageBytes = 64 * 1024;

// One channel as advertised: JSON messages described by a JSON Schema.
struct Channel {
  std::uint32_t id = 0;
  std::string topic;
  std::string schema_name;
  std::string schema;  // the JSON Schema's text
};

enum class StatusLevel : int { kInfo = 0, kWarning = 1, kError = 2 };

// {"op":"serverInfo","name":…,"capabilities":["time","parameters","parametersSubscribe"],…}
nlohmann::json server_info_json(const std::string& name);
// {"op":"advertise","channels":[{id, topic, encoding:"json", schemaName, schema,
// schemaEncoding:"jsonschema"}, …]}
nlohmann::json advertise_json(const std::vector<Channel>& channels);
// {"op":"status","level":0|1|2,"message":…}
nlohmann::json status_message(StatusLevel level, const std::string& message);
// {"op":"parameterValues","parameters":[…],"id":…}
nlohmann::json parameter_values_json(const nlohmann::json& parameters,
                                     const std::optional<std::string>& id = std::nullopt);

// Binary: opcode 0x01, the subscription id (uint32 LE), the log time (uint64 ns LE), the payload.
std::string message_data(std::uint32_t subscription_id, std::uint64_t log_time_ns,
                         std::string_view payload);
// Binary: opcode 0x02, the time (uint64 ns LE).
std::string time_message(std::uint64_t time_ns);

// --- the client's operations ---
struct Subscribe {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> subscriptions;  // (id, channelId)
};
struct Unsubscribe {
  std::vector<std::uint32_t> subscription_ids;
};
struct GetParameters {
  std::vector<std::string> names;  // empty: every parameter
  std::optional<std::string> id;
};
struct SetParameters {
  nlohmann::json parameters;  // [{name, value}, …] as sent; settings_change_of reads them
  std::optional<std::string> id;
};
struct SubscribeParameterUpdates {
  std::vector<std::string> names;
};
struct UnsubscribeParameterUpdates {
  std::vector<std::string> names;
};
struct FoxgloveError {
  std::string message;
};
using ClientOp = std::variant<Subscribe, Unsubscribe, GetParameters, SetParameters,
                              SubscribeParameterUpdates, UnsubscribeParameterUpdates,
                              FoxgloveError>;

// Never throws. Malformed JSON, an unknown or unsupported op, a missing or mistyped field: a
// FoxgloveError naming it ("subscribe: subscriptions[0].channelId: expected a whole number
// 0..4294967295").
ClientOp parse_client_op(std::string_view text);

// --- the run-time settings as parameters ---
// [{"name":"max_drop_v","value":1.5,"type":"float64"}, {"name":"load_distribution",
// "value":"off"}, {"name":"behaviours.slant_response","value":true}, …]: `settings` is the
// status' `settings` object (runtime_settings_json), one parameter per leaf.
nlohmann::json settings_parameters(const nlohmann::json& settings);
// A setParameters' [{name, value}] as the console's configure message, checked as the console's
// is (ranges, types, names): the message, or the error naming the parameter.
std::variant<ConfigureMessage, FoxgloveError> configure_of(const nlohmann::json& parameters,
                                                           const Params& params);

}  // namespace marsokhod::link::foxglove
