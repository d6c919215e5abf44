// `marsokhod soak [--hours H] [--seed N] [--out DIR] [--json]` (runner/soak.hpp).
#pragma once

#include <iosfwd>
#include <string>

#include "config/loaded_config.hpp"

namespace CLI {
class App;
}

namespace marsokhod::app {

struct SoakArgs {
  double hours = 1.0;
  std::string seed = "1";  // text: a negative or malformed seed gets its own one-line error
  std::string out;         // default: soak-seed-N, written only on a violation
  bool json = false;
};

// Adds the subcommand to `cli`, filling `args`.
CLI::App* add_soak_command(CLI::App& cli, SoakArgs& args);

// 0 without a violation, 1 with one (its recording written), 2 for a bad argument.
// The driver runs with config.params, the simulated rover is built from config.nominal.
int run_soak_command(const SoakArgs& args, const config::LoadedConfig& config, std::ostream& out,
                     std::ostream& err);

}  // namespace marsokhod::app
