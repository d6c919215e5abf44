// `marsokhod slope-sweep [--ground NAME] [--seed S] [--distance M] [--time S] [--window W]
// [--step DEG] [--drive V1] [--modes LIST]`: the steepest slope of a soft soil the simulated rover
// climbs by driving and by each gait (runner/slope_sweep.hpp), printed as a table beside [KG92]'s
// figures; --modes names the ones to sweep (driving and gait ids, comma-separated; default all).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "config/loaded_config.hpp"

namespace CLI {
class App;
}

namespace marsokhod::app {

struct SlopeSweepArgs {
  std::string ground = "sand";
  std::uint64_t seed = 1;
  double distance_m = 0.1;
  double time_s = 40.0;
  double window_s = 0.0;  // 0: the advance over the whole climb; > 0: what it still gains at the end
  double step_deg = 0.5;
  double drive_radps = 1.0;
  std::vector<std::string> modes;  // "driving" and gait ids; empty: driving and every gait
  bool shear_reload_memory = false;  // the soil's tangential reload memory (soil_params.hpp)
};

// Adds the subcommand to `cli`, filling `args` (the caller adds --seed with its seed check).
CLI::App* add_slope_sweep_command(CLI::App& cli, SlopeSweepArgs& args);

// 0 when the sweep ran (whatever it found), 2 for a bad argument.
int run_slope_sweep_command(const SlopeSweepArgs& args, const config::LoadedConfig& config,
                            std::ostream& out, std::ostream& err);

}  // namespace marsokhod::app
