// `marsokhod calibrate PROCEDURE --sim|--can URL [--out FILE] [--force] [--plot DIR] …`: runs one
// of the thesis' calibration procedures (src/calibration/procedures.hpp) on the simulated rover
// or a real bus, prints the fit and its residuals, and writes the calibration file.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>

#include "config/loaded_config.hpp"

namespace marsokhod::app {

struct CalibrateArgs {
  std::string procedure;
  bool sim = false;
  std::string can;                  // socketcan:can0 | socketcand://HOST:PORT/CHANNEL
  std::string out = "calibration.toml";
  bool force = false;
  std::string plot;                 // a folder for the measured data and its plots
  std::uint64_t seed = 1;           // the simulated unit
  std::optional<std::string> ground;  // --sim: the ground's material (default hard ground)
  std::optional<double> duration_s;
  std::optional<int> icr;
  std::string from;                 // voltage-drop: a scenario's --out folder
  bool list = false;
};

// 0: fitted and written; 1: refused (a poor fit, an existing file without --force); 2: a bad
// argument, an unreachable bus, a controller that does not answer.
int run_calibrate_command(const CalibrateArgs& args, const config::LoadedConfig& config,
                          std::istream& in, std::ostream& out, std::ostream& err);

}  // namespace marsokhod::app
