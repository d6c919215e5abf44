// `marsokhod export-mcap DIR`: an existing recording (can.log, operator.jsonl, config.toml and,
// when there, calibration.toml and telemetry.csv) turned into DIR/recording.mcap. The driver is
// re-run over it as `replay` does (replay.hpp), so a recording made before recording.mcap existed
// gets the same channels as a new one (mcap_recording.hpp):
//   from can.log:                  /can/raw, /can/decoded (every frame at its bus time)
//   from operator.jsonl:           /operator/input, /operator/runtime
//   from the replayed driver:      /status (without "truth"), /imu, /joint_states, /pose,
//                                  /pose/estimate
//   from telemetry.csv's true_*:   /tf (a recording of the simulator; absent for `drive`)
// Not rebuilt: the simulator's "truth" object inside /status (the 3-D view's wheel positions,
// slips): telemetry.csv keeps only part of it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "core/params.hpp"
#include "driver/driver.hpp"

namespace marsokhod::runner {

struct ExportResult {
  std::uint64_t cycles = 0;
  std::uint64_t messages = 0;
  bool true_pose = false;        // /tf was rebuilt from telemetry.csv
  bool identical = true;         // the replayed driver sent the recorded requests
  std::string first_difference;  // where it did not
};

// Writes folder/recording.mcap (over an existing one only with `overwrite`). Throws
// std::runtime_error with the reason: no can.log or operator.jsonl (not a recording), an
// unreadable line, recording.mcap exists.
ExportResult export_mcap(const std::filesystem::path& folder, const Params& params,
                         std::unique_ptr<driver::Driver> start = nullptr, bool overwrite = false);

}  // namespace marsokhod::runner
