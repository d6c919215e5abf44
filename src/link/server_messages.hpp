// The messages the server sends (docs/operator-protocol.md, "Server → console"): the JSON of
// each, built in one place so that the protocol document has one place to match.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "config/configuration.hpp"
#include "core/params.hpp"
#include "link/control_arbiter.hpp"

namespace marsokhod::link {

// 2: gamepad and targets carry seq and sent_ms; the server sends `stopped`; the WebSocket is
// authorised by the session cookie (or Authorization: Bearer), not ?token=.
inline constexpr int kProtocolVersion = 2;

// The largest |v_mps| and |yaw_radps| a `velocity` message may ask for: navigation's
// max_velocity_mps and max_yaw_rate_radps of the driver's parameters (r·v1ᵈ, r·v2ᵈ/(t/2)).
struct VelocityLimits {
  double v_mps = 0.0;
  double yaw_radps = 0.0;
};
VelocityLimits velocity_limits(const Params& params);

// {"type":"hello","protocol":1,"client_id":N,"controller":M|null,"read_only":bool,...}
// `calibration` names the calibration file the driver loaded on top of the configuration (null
// when it runs on the configuration's nominal values) and the procedures in it;
// `velocity_limits` {"v_mps","yaw_radps"} the limits above, so that a console can scale its
// sticks to them.
nlohmann::json hello_json(ClientId client, std::optional<ClientId> controller,
                          const config::CalibrationSource& calibration,
                          const VelocityLimits& limits);

// {"type":"control","controller":M|null,"read_only":bool,"lost_control":bool,"reason":"…"},
// as `recipient` sees it: lost_control is true for the client that held control before.
nlohmann::json control_json(const ControlChange& change, ClientId recipient);

// {"type":"error","field":"…","message":"…"}
nlohmann::json error_json(const MessageError& error);

// {"type":"stopped","by":N,"reason":"client 3 pressed STOP"}: to every console, for every stop.
nlohmann::json stopped_json(const StopNotice& notice);

// {"type":"pong"}
nlohmann::json pong_json();

// {"type":"status","status":{…}}: the object publish_status was given, unchanged.
nlohmann::json status_envelope(const nlohmann::json& status);

// The JSON text as sent: invalid UTF-8 in a string (a garbled fault text, say) is replaced by
// U+FFFD instead of failing the whole message.
std::string wire_text(const nlohmann::json& message);

}  // namespace marsokhod::link
