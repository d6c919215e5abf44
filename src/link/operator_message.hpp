// The operator console's messages (JSON text over the WebSocket), parsed into values before any
// of them reaches the driver. docs/operator-protocol.md is the reference for every field, type,
// unit and range; this header is its code. The parser is pure and strict: anything it does not
// understand exactly — malformed JSON, a duplicate or unknown key, a wrong type, a number that
// is not finite or out of range — is an error naming the field, so that a console bug shows up
// as a message on the console instead of as a rover doing something nobody asked for.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include <nlohmann/json.hpp>

#include "core/mobility/gait_table.hpp"
#include "core/mobility/gamepad.hpp"
#include "core/params.hpp"
#include "driver/motion_controller.hpp"
#include "driver/operator_channel.hpp"

namespace marsokhod::link {

// Longer texts are rejected before parsing: the largest legal message (a gamepad reading with
// every number written out in full) is well under 2 KiB.
inline constexpr std::size_t kMaxOperatorMessageBytes = 4096;

// Every gamepad and targets message carries its place in the console's stream: `seq` counts up
// from 1 on each connection and `sent_ms` is the console's clock when it sent it (any epoch,
// milliseconds). The server drops a message whose seq is not above the last one's, or that is
// older than the others by more than ServerOptions::max_input_age_s (input_freshness.hpp), so a
// burst of old readings after a network stall cannot restart motion.
struct InputStamp {
  std::uint64_t seq = 0;  // 0 .. 2^53 − 1 (what a JavaScript number holds exactly)
  double sent_ms = 0.0;   // 0 .. 1e15 ms
  bool operator==(const InputStamp&) const = default;
};

// {"type":"gamepad","seq":…,"sent_ms":…,"axes":[4 numbers in −1..1],"buttons":[17 booleans]},
// W3C standard mapping.
struct GamepadMessage {
  InputStamp stamp;
  std::array<double, mobility::kGamepadAxisCount> axes{};
  std::array<bool, mobility::kGamepadButtonCount> buttons{};
  bool operator==(const GamepadMessage&) const = default;
};

// {"type":"targets", …}: the mapping's output directly. A key left out means 0, "none", false:
// each message is complete, so a lost one cannot leave a stale value behind.
struct TargetsMessage {
  InputStamp stamp;
  double v1_radps = 0.0;  // |v1| ≤ max_drive_speed_radps
  double v2_radps = 0.0;  // |v2| ≤ max_spin_speed_radps
  double v4_radps = 0.0;  // |v4| ≤ max_trench_speed_radps
  double v6_radps = 0.0;  // |v6| ≤ max_no_load_speed_radps (w)
  double v7_radps = 0.0;  // |v7| ≤ w
  mobility::Gait gait = mobility::Gait::kNone;
  double gait_speed = 0.0;  // s ∈ [−1, 1]
  bool calibration_mode = false;
  bool operator==(const TargetsMessage&) const = default;
};

struct StopMessage {
  bool operator==(const StopMessage&) const = default;
};
struct ClearFaultsMessage {
  bool operator==(const ClearFaultsMessage&) const = default;
};
struct TakeControlMessage {
  bool operator==(const TakeControlMessage&) const = default;
};
struct ReleaseControlMessage {
  bool operator==(const ReleaseControlMessage&) const = default;
};
struct PingMessage {
  bool operator==(const PingMessage&) const = default;
};

// {"type":"configure", …}: RuntimeSettings; a key left out leaves that setting as it is.
struct ConfigureMessage {
  std::optional<double> max_drop_v;  // Υ of (6.3), (0, 10] V
  std::optional<LoadDistributionMode> load_distribution;  // "off" | "v" (6.5) | "s" (6.6)
  std::optional<bool> power_management;
  std::optional<bool> slant_response;
  std::optional<bool> contract_on_turn;
  std::optional<bool> axle_placement;
  std::optional<double> speed_scale;  // [0, 1]
  bool operator==(const ConfigureMessage&) const = default;
};

// Why a message was rejected. `field` is a path into the message ("axes[1]",
// "behaviours.slant_response", "type"), or "json" when the text is not a JSON object at all.
struct MessageError {
  std::string field;
  std::string message;
  bool operator==(const MessageError&) const = default;
};

using OperatorMessage =
    std::variant<GamepadMessage, TargetsMessage, StopMessage, ClearFaultsMessage,
                 TakeControlMessage, ReleaseControlMessage, ConfigureMessage, PingMessage>;
using ParseResult =
    std::variant<GamepadMessage, TargetsMessage, StopMessage, ClearFaultsMessage,
                 TakeControlMessage, ReleaseControlMessage, ConfigureMessage, PingMessage,
                 MessageError>;

// Never throws. Ranges come from `params` (operator_input, motors.max_no_load_speed_radps).
ParseResult parse_operator_message(std::string_view json, const Params& params);

// The message of a successful parse; nullopt for a MessageError.
std::optional<OperatorMessage> message_of(const ParseResult& result);

// The "type" string of a message: "gamepad", "targets", "stop", ….
std::string_view message_type(const OperatorMessage& message);

// The message as the console writes it, every key present: parse_operator_message of its dump
// gives the message back (the round trip the tests and the fuzzer check).
nlohmann::json operator_message_json(const OperatorMessage& message);

std::string_view load_distribution_id(LoadDistributionMode mode);

// The stamp of a gamepad or targets message; nullopt for the others (they are never stale: a
// late stop is still a stop).
std::optional<InputStamp> input_stamp(const OperatorMessage& message);

// What the driver takes from a message: gamepad, targets, stop and clear_faults become an
// OperatorInput (for targets, the gamepad memory is the driver's); the others give nullopt.
std::optional<driver::OperatorInput> operator_input(const OperatorMessage& message);

// The settings after a configure message: the keys it carries replace those of `current`.
driver::RuntimeSettings apply_configuration(const ConfigureMessage& message,
                                            driver::RuntimeSettings current);

}  // namespace marsokhod::link
