// The channels the rover offers to Foxglove and other MCAP tools: JSON messages with their JSON
// Schemas, built once for both places they go — recording.mcap (mcap_recording.hpp) and the link
// server's live Foxglove WebSocket (live_console.hpp, link/foxglove_protocol.hpp).
//   /status          link::status_json, the console's status (in the simulator with its truth)
//   /imu             µ8's sensors: accel_mps2 (a1, a2, a3), yaw_rate_radps, the axles' tilts, slope
//                    σ, the estimated roll and pitch
//   /joint_states    the eight motors by their URDF joint names (wheel_FL … wheel_BR, joint_AF,
//                    joint_AR): position p, velocity w, effort τ, commanded v, duty d
//   /pose            the pose estimate (status.pose) as foxglove.PoseInFrame in frame "world"
//   /pose/estimate   status.pose's numbers (x_m, y_m, heading_rad, speed, σ …)
//   /tf              the simulator only: the true pose of base_link in "world", as
//                    foxglove.FrameTransform
//   /tf/links        the simulator only: every URDF joint's transform (parent link → child link)
//                    at the true joint angles, as foxglove.FrameTransforms
//   /can/raw         every frame on the bus at its bus time: direction rx (to the driver) or tx
//   /can/decoded     every frame as `marsokhod decode --json` prints it
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/params.hpp"
#include "core/protocol/frame_description.hpp"
#include "driver/status.hpp"
#include "sim/physics/rover_kinematics.hpp"

namespace marsokhod::runner {

// One message: its topic, its schema's name and the JSON text.
struct ChannelMessage {
  std::string topic;
  std::string schema_name;
  std::string text;
};

// The true pose of the center unit (sim::GroundTruth's position and roll, pitch, yaw) and, when
// known, the links' transforms at the true joint angles (none in an export from telemetry.csv).
struct TruePose {
  std::array<double, 3> position_m{};
  std::array<double, 3> roll_pitch_yaw_rad{};
  std::vector<sim::LinkTransform> links;
};
TruePose true_pose_of(const sim::GroundTruth& truth, const std::vector<sim::RoverJoint>& joints);

// "marsokhod.status" for "/status": our own messages' schema names.
std::string schema_name_of(const std::string& topic);

// The JSON Schema of a channel: Foxglove's own for foxglove.* names, else json_schema_of(first),
// titled `schema_name`.
nlohmann::json channel_schema(const std::string& schema_name, const nlohmann::json& first);

// The JSON Schema (draft 2020-12 keywords only: type, properties, items, title) of a value's
// shape: the channels' schemas of their own messages. null (a non-finite number) allows any.
nlohmann::json json_schema_of(const nlohmann::json& value);

// The channels of one cycle's status and truth, in this order: /status, /imu, /joint_states,
// /pose, /pose/estimate (with a status), /tf, /tf/links (with a true pose, the latter when it has
// links). `truth`: the simulator's truth_json for /status, or null.
std::vector<ChannelMessage> status_channel_messages(std::int64_t time_us,
                                                    const driver::DriverStatus* status,
                                                    const nlohmann::json& truth,
                                                    const std::optional<TruePose>& true_pose);

// /can/raw and /can/decoded, decoded in the bus' context (a configuration request's icr and con
// change how the frames after it read): every frame must pass through add, in bus order.
class CanChannels {
 public:
  explicit CanChannels(const Params& params);
  // Takes `frame` into the context; appends its two messages to `out` unless it is nullptr.
  void add(std::int64_t time_us, const protocol::CanFrame& frame, bool received,
           std::vector<ChannelMessage>* out);

 private:
  protocol::BusContext bus_;
};

}  // namespace marsokhod::runner
