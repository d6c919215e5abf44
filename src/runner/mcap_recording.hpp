// recording.mcap: a recording's cycles as MCAP (mcap_writer.hpp) for Foxglove, PlotJuggler and
// other MCAP tools. JSON messages (message encoding `json`, schemas `jsonschema`); log time and
// publish time are the rover's mission time (in the simulator: simulated time) in ns, so the same
// seed gives the same bytes. Channels (docs/recordings.md describes them): those of
// channel_messages.hpp — /status, /imu, /joint_states, /pose, /pose/estimate, /tf and /tf/links
// (simulator), /can/raw, /can/decoded — and
//   /operator/input  the operator's input of a cycle that had one
//   /operator/runtime the run-time settings, when they changed
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
#include "runner/channel_messages.hpp"
#include "runner/mcap_writer.hpp"

namespace marsokhod::runner {

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
  void publish(std::int64_t time_us, const ChannelMessage& message);

  std::filesystem::path file_;
  std::ofstream out_;
  std::unique_ptr<McapWriter> writer_;
  CanChannels can_;
  std::map<std::string, std::uint16_t> channels_;
};

// Reads a whole file's text ("" when `path` is empty); throws std::runtime_error naming it.
std::string read_text_file(const std::filesystem::path& path);

}  // namespace marsokhod::runner
