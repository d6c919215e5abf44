// The commands that run in real time: `marsokhod run` (simulator + driver + console in one
// process), `marsokhod sim` (the simulated rover served over socketcand) and `marsokhod drive`
// (the driver on a real or remote bus, with the console). Pacing (live_pacing.hpp), sockets and
// signals live here, outside the deterministic cycle: the cycle still takes time as a value.
//
// `run` and `drive` are one loop, one cycle every h: wait for the cycle, take the console's
// commands (live_console.hpp), step the driver, publish its status. They differ only in what
// answers the driver on the bus: the simulated rover in this process (with a scenario's faults
// and a recording), or a CAN transport.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>

#include "config/loaded_config.hpp"
#include "core/params.hpp"
#include "runner/live_console.hpp"

namespace marsokhod::runner {

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
  std::string firmware;  // a folder of mu0..mu8.elf: the real firmware in simavr (sim/avr)
};

struct DriveArgs {
  std::string can;              // socketcan:can0 | socketcand://HOST:PORT/CHANNEL
  ConsoleArgs console;
  double duration_s = 0.0;
  bool quiet = false;
  // The joint state kept across restarts (joint_memory_file.hpp); empty: none kept, a restart
  // runs Procedure 4.3 and takes the joints to be vertical.
  std::string joint_memory;
  // A folder for can.log, operator.jsonl, telemetry.csv (no truth columns) and recording.mcap;
  // the frames a cycle received are stamped with the cycle's time. Empty: none.
  std::string record;
};

// The exit status: 0 when stopped (signal or duration), 1 when the bus failed, 2 when the
// arguments, files or addresses are not usable (one line on `err`).
// The driver runs with config.params, the simulated rover is built from config.nominal.
int run_live(const RunArgs& args, const config::LoadedConfig& config, std::ostream& out,
             std::ostream& err);
int run_sim(const SimArgs& args, const Params& params, std::ostream& out, std::ostream& err);
int run_drive(const DriveArgs& args, const config::LoadedConfig& config, std::ostream& out,
              std::ostream& err);

}  // namespace marsokhod::runner
