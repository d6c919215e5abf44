#include "link/server_messages.hpp"

#include "core/navigation/mission.hpp"

namespace marsokhod::link {
namespace {

nlohmann::json optional_id(std::optional<ClientId> id) {
  return id ? nlohmann::json(*id) : nlohmann::json(nullptr);
}

}  // namespace

VelocityLimits velocity_limits(const Params& params) {
  return {navigation::max_velocity_mps(params), navigation::max_yaw_rate_radps(params)};
}

nlohmann::json hello_json(ClientId client, std::optional<ClientId> controller,
                          const config::CalibrationSource& calibration,
                          const VelocityLimits& limits) {
  return {{"type", "hello"},
          {"protocol", kProtocolVersion},
          {"client_id", client},
          {"controller", optional_id(controller)},
          {"read_only", controller != client},
          {"calibration",
           {{"file", calibration.file.empty() ? nlohmann::json(nullptr)
                                              : nlohmann::json(calibration.file)},
            {"procedures", calibration.procedures}}},
          {"velocity_limits", {{"v_mps", limits.v_mps}, {"yaw_radps", limits.yaw_radps}}}};
}

nlohmann::json control_json(const ControlChange& change, ClientId recipient) {
  const bool lost = change.previous == recipient && change.controller != recipient;
  return {{"type", "control"},
          {"controller", optional_id(change.controller)},
          {"read_only", change.controller != recipient},
          {"lost_control", lost},
          {"reason", change.reason}};
}

nlohmann::json error_json(const MessageError& error) {
  return {{"type", "error"}, {"field", error.field}, {"message", error.message}};
}

nlohmann::json stopped_json(const StopNotice& notice) {
  return {{"type", "stopped"}, {"by", notice.by}, {"reason", notice.reason}};
}

nlohmann::json pong_json() { return {{"type", "pong"}}; }

nlohmann::json status_envelope(const nlohmann::json& status) {
  return {{"type", "status"}, {"status", status}};
}

std::string wire_text(const nlohmann::json& message) {
  return message.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace marsokhod::link
