// What a run leaves behind in its output folder, enough to replay it exactly and to plot it:
//   can.log         every frame on the bus, candump log format (can-utils, python-can read it);
//                   per cycle, the frames the driver received, then the requests it sent at t_k
//   operator.jsonl  one line per cycle: {"t": "12.345600", "rx": N, "input": {…}|null,
//                   "runtime": {…} (only when it changed), "running": bool}
//   telemetry.csv   one row per cycle: every status field of the driver and the simulator's truth
//   config.toml     the configuration the driver ran with
//   recording.mcap  (when given the Params) the same cycles as MCAP for Foxglove and PlotJuggler
//                   (mcap_recording.hpp)
#pragma once

#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include "driver/operator_commands.hpp"
#include "runner/mcap_recording.hpp"
#include "runner/session.hpp"

namespace marsokhod::runner {

// "12.345600": whole microseconds as candump writes them.
std::string format_time_us(std::int64_t time_us);
// The inverse; throws std::invalid_argument for anything but digits '.' six digits.
std::int64_t parse_time_us(const std::string& text);

class Recorder {
 public:
  // Creates the folder; throws std::runtime_error naming the path if it cannot be written.
  // Copies config_file to config.toml and, when one is given, the calibration file the driver
  // ran with to calibration.toml: replay needs the driver's exact Params.
  // `mcap_params`: also write recording.mcap, its frames decoded with these Params; `source`
  // names the command in its metadata.
  Recorder(const std::filesystem::path& folder, const std::filesystem::path& config_file,
           const std::filesystem::path& calibration_file = {},
           const Params* mcap_params = nullptr, const std::string& source = "");

  // A cycle of the simulated rover and the driver.
  void record(const CycleRecord& cycle, const std::optional<driver::RuntimeSettings>& runtime,
              const driver::DriverStatus& status, const sim::SimulatedRover& rover);
  // A cycle of the driver on a bus (`drive`): no truth; telemetry.csv's truth columns are empty.
  void record(const CycleRecord& cycle, const std::optional<driver::RuntimeSettings>& runtime,
              const driver::DriverStatus& status);
  // Closes recording.mcap (its summary); throws std::runtime_error when it could not be written.
  // The destructor does it too, silently.
  void finish();

 private:
  void record(const CycleRecord& cycle, const std::optional<driver::RuntimeSettings>& runtime,
              const driver::DriverStatus& status, const sim::SimulatedRover* rover);

  std::ofstream can_;
  std::ofstream operator_;
  std::ofstream telemetry_;
  std::unique_ptr<McapRecording> mcap_;
  std::vector<sim::RoverJoint> joints_;  // the URDF's, for /tf/links
};

}  // namespace marsokhod::runner
