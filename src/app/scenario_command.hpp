// `marsokhod scenario` and `marsokhod replay`.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "config/loaded_config.hpp"
#include "core/params.hpp"

namespace marsokhod::app {

struct ScenarioArgs {
  std::string name;  // a shipped scenario's name or a file
  std::optional<std::uint64_t> seed;
  std::string out;
  bool json = false;
  bool list = false;
  bool no_plots = false;
  std::string firmware;  // a folder of mu0..mu8.elf: the real firmware in simavr
  std::optional<double> physics_step_ms;  // MuJoCo's step; unset: the simulator's default
  // A sweep: --all and/or --seeds A-B, run as child processes of `program`, `jobs` at a time.
  bool all = false;
  std::string seeds;
  std::size_t jobs = 0;  // 0: one per core
  std::string program;   // this executable
  bool progress = false; // a progress line on standard error (a terminal)
};

// 0 when every run of the sweep passed, 1 when one failed, 2 for a bad argument.
int run_sweep_command(const ScenarioArgs& args, const config::LoadedConfig& config, std::ostream& out,
                      std::ostream& err);

// The folders searched for NAME.toml: $MARSOKHOD_SCENARIOS, ./scenarios, the source tree's.
std::vector<std::filesystem::path> scenario_folders();

// 0 when every check passed, 1 when one failed, 2 for a bad argument or scenario file.
// The driver runs with config.params, the simulated rover is built from config.nominal.
int run_scenario_command(const ScenarioArgs& args, const config::LoadedConfig& config, std::ostream& out,
                         std::ostream& err);

// `export-mcap DIR`: DIR/recording.mcap from the recording in DIR (runner/export_mcap.hpp), with
// its own config.toml as replay does. 0 when written; 1 when written but the replayed driver
// differed from the recording (its status channels then are the replayed driver's); 2 when it
// cannot be made (no can.log, an unreadable line, recording.mcap exists without `overwrite`).
int run_export_mcap_command(const std::string& folder, bool overwrite, const Params& params,
                            std::ostream& out, std::ostream& err);

// 0 when the replay is identical to the recording, 1 when it differs, 2 when it cannot be read.
// The recording's own config.toml (and calibration.toml on top) is used when it has one.
int run_replay_command(const std::string& folder, const Params& params, std::ostream& out,
                       std::ostream& err);

}  // namespace marsokhod::app
