// What a run leaves behind in its output folder, enough to replay it exactly and to plot it:
//   can.log         every frame on the bus, candump log format (can-utils, python-can read it);
//                   per cycle, the frames the driver received, then the requests it sent at t_k
//   operator.jsonl  one line per cycle: {"t": "12.345600", "rx": N, "input": {…}|null,
//                   "runtime": {…} (only when it changed), "running": bool}
//   telemetry.csv   one row per cycle: every status field of the driver and the simulator's truth
//   config.toml     the configuration the driver ran with
#pragma once

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "driver/operator_commands.hpp"
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
  Recorder(const std::filesystem::path& folder, const std::filesystem::path& config_file,
           const std::filesystem::path& calibration_file = {});

  void record(const CycleRecord& cycle, const std::optional<driver::RuntimeSettings>& runtime,
              const driver::DriverStatus& status, const sim::SimulatedRover& rover);

 private:
  std::ofstream can_;
  std::ofstream operator_;
  std::ofstream telemetry_;
};

}  // namespace marsokhod::runner
