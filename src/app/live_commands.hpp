// The commands that run in real time: `marsokhod run` (simulator + driver + console in one
// process), `marsokhod sim` (the simulated rover served over socketcand) and `marsokhod drive`
// (the driver on a real or remote bus, with the console). Real-time pacing, sockets and signals
// live here, outside the deterministic cycle: the cycle still takes time as a value.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>

#include "app/loaded_config.hpp"
#include "core/params.hpp"

namespace marsokhod::app {

// Empty or zero: the configuration's [console] values.
struct ConsoleArgs {
  std::string listen;
  std::string token;            // visible to every user in `ps`: prefer token_file or the environment
  std::string token_file;       // the token in a file only its owner may read (mode 0600)
  std::string web;              // the console's build; empty: web/dist of the working folder or source tree
  bool no_console = false;
  double status_rate_hz = 0.0;
};

struct RunArgs {
  ConsoleArgs console;
  std::string scenario;         // terrain and faults from a scenario file (its inputs are ignored)
  std::uint64_t seed = 1;
  double duration_s = 0.0;      // 0: until SIGINT/SIGTERM
  std::string record;           // a folder for can.log, operator.jsonl, telemetry.csv
  bool quiet = false;           // no status line in the terminal
};

struct SimArgs {
  std::string listen = "127.0.0.1:29536";
  std::string channel = "can0";
  std::string scenario;
  std::uint64_t seed = 1;
  double duration_s = 0.0;
};

struct DriveArgs {
  std::string can;              // socketcan:can0 | socketcand://HOST:PORT/CHANNEL
  ConsoleArgs console;
  double duration_s = 0.0;
  bool quiet = false;
};

// The driver runs with config.params, the simulated rover is built from config.nominal.
int run_live(const RunArgs& args, const LoadedConfig& config, std::ostream& out,
             std::ostream& err);
int run_sim(const SimArgs& args, const Params& params, std::ostream& out, std::ostream& err);
int run_drive(const DriveArgs& args, const LoadedConfig& config, std::ostream& out,
              std::ostream& err);

// Where the console's files are: the given folder, else ./web/dist, else the source tree's.
std::optional<std::filesystem::path> find_web_dist(const std::string& given);

}  // namespace marsokhod::app
