// recording.mcap: a recording's cycles as MCAP (mcap_writer.hpp) for Foxglove, PlotJuggler and
// other MCAP tools. JSON messages (message encoding `json`, schemas `jsonschema`); log time and
// publish time are the rover's mission time (in the simulator: simulated time) in ns, so the same
// seed gives the same bytes. Channels (docs/recordings.md describes them):
//   /status          every cycle the driver ran: link::status_json, the console's status message
//                    (in the simulator with its "truth")
//   /imu             µ8's sensors: accel_mps2 (a1, a2, a3), yaw_rate_radps, the axles' tilts, slope
//                    σ, the estimated roll and pitch
//   /joint_states    the eight motors by their URDF joint names (wheel_FL … wheel_BR, joint_AF,
//                    joint_AR): position p, velocity w, effort τ, commanded v, duty d
//   /pose            the pose estimate (status.pose) as foxglove.PoseInFrame in frame "world"
//   /pose/estimate   status.pose's numbers (x_m, y_m, heading_rad, speed, σ …)
//   /can/raw         every frame on the bus at its bus time: direction rx (to the driver) or tx
//   /can/decoded     every frame as `marsokhod decode --json` prints it
//   /operator/input  the operator's input of a cycle that had one
//   /operator/runtime the run-time settings, when they changed
//   /tf              the simulator only: the true pose of base_link in "world", as
//                    foxglove.FrameTransform
// and the configuration as attachments (config.toml, calibration.toml) and the metadata
// "marsokhod".
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/params.hpp"
#include "core/protocol/frame_description.hpp"
#include "driver/operator_commands.hpp"
#include "driver/status.hpp"
#include "runner/mcap_writer.hpp"

namespace marsokhod::runner {

// The true pose of the center unit (sim::GroundTruth's position and roll, pitch, yaw).
struct TruePose {
  std::array<double, 3> position_m{};
  std::array<double, 3> roll_pitch_yaw_rad{};
};

// One cycle as the recording sees it.
struct McapCycle {
  std::int64_t time_us = 0;
  std::vector<std::pair<std::int64_t, protocol::CanFrame>> received;  // (bus time µs, frame)
  std::vector<protocol::CanFrame> sent;                               // at time_us
  const driver::OperatorInput* input = nullptr;
  std::optional<driver::RuntimeSettings> runtime;  // when changed
  const driver::DriverStatus* status = nullptr;    // nullptr: the driver was not running
  nlohmann::json truth;                            // the simulator's truth_json, or null
  std::optional<TruePose> true_pose;
};

class McapRecording {
 public:
  // Opens `file`; throws std::runtime_error naming it if it cannot be written. `source` names the
  // command (metadata); config/calibration: the files' text, attached when not empty.
  McapRecording(const std::filesystem::path& file, const Params& params, const std::string& source,
                const std::string& config_text, const std::string& calibration_text = "");
  ~McapRecording();

  void record(const McapCycle& cycle);
  // Writes the summary and closes the file; throws std::runtime_error when it failed.
  void finish();

  std::uint64_t message_count() const { return writer_->message_count(); }

 private:
  std::uint16_t channel(const std::string& topic, const nlohmann::json& first,
                        const std::string& schema_name);
  void publish(const std::string& topic, std::int64_t time_us, const nlohmann::json& message,
               const char* schema_name = nullptr);
  void publish_ordered(const std::string& topic, std::int64_t time_us,
                       const nlohmann::ordered_json& message);
  void record_frame(std::int64_t time_us, const protocol::CanFrame& frame, bool received);

  std::filesystem::path file_;
  std::ofstream out_;
  std::unique_ptr<McapWriter> writer_;
  protocol::BusContext bus_;
  std::map<std::string, std::uint16_t> channels_;
};

// The JSON Schema (draft 2020-12 keywords only: type, properties, items, title) of a value's
// shape: the recordings' schemas of their own messages. null (a non-finite number) allows any.
nlohmann::json json_schema_of(const nlohmann::json& value);

// Reads a whole file's text ("" when `path` is empty); throws std::runtime_error naming it.
std::string read_text_file(const std::filesystem::path& path);

}  // namespace marsokhod::runner
