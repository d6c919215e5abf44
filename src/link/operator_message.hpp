// The operator console's messages (JSON text over the WebSocket), parsed into values before any
// of them reaches the driver. docs/operator-protocol.md is the reference for every field, type,
// unit and range; this header is its code, with the commands' own fields read by the codec the
// recordings share (command_json.hpp) and their ranges those of driver/operator_commands.hpp.
// The parser is pure and strict: anything it does not understand exactly — malformed JSON, a
// duplicate or unknown key, a wrong type, a number that is not finite or out of range — is an
// error naming the field, so that a console bug shows up as a message on the console instead of
// as a rover doing something nobody asked for.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include <nlohmann/json.hpp>

#include "core/mobility/gamepad.hpp"
#include "core/params.hpp"
#include "driver/operator_commands.hpp"

namespace marsokhod::link {

// Longer texts are rejected before parsing: the largest legal message (a goto of 64 waypoints
// with every number written out in full, ≈ 64 × 50 bytes) is well under 8 KiB.
inline constexpr std::size_t kMaxOperatorMessageBytes = 8192;

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
  mobility::GamepadState reading;
  bool operator==(const GamepadMessage&) const = default;
};

// {"type":"targets", …}: the mapping's output directly (v1 v2 v3 v4 v6 v7 gait gait_speed
// calibration_mode; joint buttons and joint targets are not the console's). A key left out means
// 0, "none", false: each message is complete, so a lost one cannot leave a stale value behind.
struct TargetsMessage {
  InputStamp stamp;
  mobility::OperatorTargets targets;
  bool operator==(const TargetsMessage&) const = default;
};

// {"type":"velocity","seq":…,"sent_ms":…,"v_mps":…,"yaw_radps":…}: cmd_vel, a stream like
// targets (core/navigation/mission.hpp maps it onto m1 and m2).
struct VelocityMessage {
  InputStamp stamp;
  navigation::VelocityCommand command;
  bool operator==(const VelocityMessage&) const = default;
};

// {"type":"mission","seq":…,"sent_ms":…,"kind":"turn"|"move"|"goto", …}: starts a mission.
struct MissionMessage {
  InputStamp stamp;
  navigation::MissionRequest request;
  bool operator==(const MissionMessage&) const = default;
};

// {"type":"heartbeat","seq":…,"sent_ms":…}: keeps a running mission alive.
struct HeartbeatMessage {
  InputStamp stamp;
  bool operator==(const HeartbeatMessage&) const = default;
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

// {"type":"configure", …}: a key left out leaves that setting as it is.
struct ConfigureMessage {
  driver::SettingsChange change;
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
                 TakeControlMessage, ReleaseControlMessage, ConfigureMessage, PingMessage,
                 VelocityMessage, MissionMessage, HeartbeatMessage>;
using ParseResult =
    std::variant<GamepadMessage, TargetsMessage, StopMessage, ClearFaultsMessage,
                 TakeControlMessage, ReleaseControlMessage, ConfigureMessage, PingMessage,
                 VelocityMessage, MissionMessage, HeartbeatMessage, MessageError>;

// Never throws. Ranges come from `params` (operator_input, motors.max_no_load_speed_radps).
ParseResult parse_operator_message(std::string_view json, const Params& params);

// The message of a successful parse; nullopt for a MessageError.
std::optional<OperatorMessage> message_of(const ParseResult& result);

// The "type" string of a message: "gamepad", "targets", "stop", ….
std::string_view message_type(const OperatorMessage& message);

// The message as the console writes it, every key present: parse_operator_message of its dump
// gives the message back (the round trip the tests and the fuzzer check).
nlohmann::json operator_message_json(const OperatorMessage& message);

// The stamp of a gamepad, targets, velocity, mission or heartbeat message; nullopt for the others (they are never stale: a
// late stop is still a stop).
std::optional<InputStamp> input_stamp(const OperatorMessage& message);

// What the driver takes from a message: gamepad, targets, velocity, mission, heartbeat, stop and
// clear_faults become an OperatorInput (for targets, the gamepad memory is the driver's); the others give nullopt.
std::optional<driver::OperatorInput> operator_input(const OperatorMessage& message);

}  // namespace marsokhod::link
