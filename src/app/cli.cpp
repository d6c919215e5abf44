#include "app/cli.hpp"

#include <CLI/CLI.hpp>

#include <unistd.h>

#include <cstdlib>
#include <iostream>
#include <fstream>
#include <istream>
#include <ostream>

#include "app/calibrate_command.hpp"
#include "app/decode_command.hpp"
#include "app/number_checks.hpp"
#include "app/scenario_command.hpp"
#include "app/slope_sweep_command.hpp"
#include "app/soak_command.hpp"
#include "config/calibration.hpp"
#include "config/load_params.hpp"
#include "runner/live.hpp"
#include "sim/physics/rover_urdf.hpp"

namespace marsokhod::app {
namespace {

constexpr int kUsageError = 2;

// CLI11 reads "-1" into an unsigned seed as 2^64 − 1; a negative seed is a mistake, say so.
const CLI::Validator kSeed(
    [](std::string& text) -> std::string {
      const auto first = text.find_first_not_of(" \t");
      if (first != std::string::npos && text[first] == '-') {
        return text + " is negative; a seed is an integer ≥ 0";
      }
      return {};
    },
    "INTEGER ≥ 0");

struct DecodeArgs {
  std::string file;
  bool json = false;
};

int run_decode(const DecodeArgs& args, const Params& params, std::istream& in, std::ostream& out,
               std::ostream& err) {
  const DecodeOptions options{args.json};
  if (args.file == "-") return decode_trace(in, "<stdin>", params, options, out, err);
  std::ifstream file(args.file);
  if (!file) {
    err << "marsokhod decode: cannot open '" << args.file << "': no such file or not readable\n";
    return kUsageError;
  }
  return decode_trace(file, args.file, params, options, out, err);
}

}  // namespace

std::optional<std::filesystem::path> find_config(const std::string& given) {
  namespace fs = std::filesystem;
  if (!given.empty()) return fs::path(given);
  if (const char* env = std::getenv("MARSOKHOD_CONFIG"); env != nullptr && *env != '\0') {
    return fs::path(env);
  }
  std::error_code ec;
  if (fs::exists("config/marsokhod.toml", ec)) return fs::path("config/marsokhod.toml");
  const fs::path source_tree = fs::path(MARSOKHOD_SOURCE_DIR) / "config" / "marsokhod.toml";
  if (fs::exists(source_tree, ec)) return source_tree;
  return std::nullopt;
}

std::string find_web_dist(const std::string& given) {
  std::error_code ec;
  if (!given.empty()) return given;
  if (std::filesystem::is_regular_file("web/dist/index.html", ec)) return "web/dist";
  const auto tree = std::filesystem::path(MARSOKHOD_SOURCE_DIR) / "web" / "dist";
  if (std::filesystem::is_regular_file(tree / "index.html", ec)) return tree.string();
  return "";
}

namespace {

// Every subcommand's arguments, bound to CLI11 by reference: built in place, never moved.
struct Commands {
  DecodeArgs decode;
  ScenarioArgs scenario;
  std::uint64_t scenario_seed = 0;
  runner::RunArgs run;
  runner::SimArgs sim;
  runner::DriveArgs drive;
  CalibrateArgs calibrate;
  SoakArgs soak;
  SlopeSweepArgs slope_sweep;
  std::string replay_dir;
  CLI::App* decode_cmd = nullptr;
  CLI::App* scenario_cmd = nullptr;
  CLI::Option* scenario_seed_option = nullptr;
  CLI::App* run_cmd = nullptr;
  CLI::App* sim_cmd = nullptr;
  CLI::App* drive_cmd = nullptr;
  CLI::App* calibrate_cmd = nullptr;
  CLI::App* soak_cmd = nullptr;
  CLI::App* slope_sweep_cmd = nullptr;
  CLI::App* replay_cmd = nullptr;
  CLI::App* urdf_cmd = nullptr;
  CLI::App* export_cmd = nullptr;
  std::string export_dir;
  bool export_force = false;
};

void add_console_options(CLI::App* cmd, runner::ConsoleArgs& c) {
  cmd->add_option("--listen", c.listen, "the console's ADDR:PORT (default: [console] listen)");
  cmd->add_option("--token", c.token,
                  "the console's access token (others see it in ps: prefer --token-file or "
                  "$MARSOKHOD_TOKEN; default: [console] token, or generated)");
  cmd->add_option("--token-file", c.token_file,
                  "read the console's access token from FILE (mode 0600)");
  cmd->add_option("--web", c.web, "the console's build folder (default web/dist)");
  cmd->add_flag("--no-console", c.no_console, "no HTTP/WebSocket server");
  cmd->add_option("--status-rate", c.status_rate_hz, "status messages per second")
      ->check(finite_range(1.0, 64.0));
}

void add_offline_commands(CLI::App& cli, Commands& c) {
  DecodeArgs& decode = c.decode;
  c.decode_cmd =
      cli.add_subcommand("decode", "decode a CAN trace in candump log format, one frame a line");
  c.decode_cmd->add_option("FILE", decode.file, "candump log file, or - for standard input")
      ->required();
  c.decode_cmd->add_flag("--json", decode.json, "print one JSON object a line");
  c.urdf_cmd = cli.add_subcommand(
      "urdf", "print the rover as a URDF, generated from the configuration's geometry");

  ScenarioArgs& scenario = c.scenario;
  CLI::App* cmd = c.scenario_cmd = cli.add_subcommand(
      "scenario", "run a scenario headless, faster than real time, and check its results");
  cmd->add_option("NAME", scenario.name, "a shipped scenario's name, or a scenario file");
  c.scenario_seed_option =
      cmd->add_option("--seed", c.scenario_seed, "the simulator's seed")->check(kSeed);
  cmd->add_option("--out", scenario.out,
                  "write can.log, operator.jsonl, telemetry.csv, recording.mcap and plots here");
  cmd->add_flag("--json", scenario.json, "print one JSON object");
  cmd->add_flag("--list", scenario.list, "name the shipped scenarios");
  cmd->add_flag("--no-plots", scenario.no_plots, "skip the gnuplot PNGs");
  cmd->add_flag("--all", scenario.all, "every shipped scenario (a sweep)");
  cmd->add_option("--seeds", scenario.seeds,
                  "a sweep over the seeds A-B (each seed a different rover unit)");
  cmd->add_option("--jobs", scenario.jobs, "runs at once in a sweep (default: one per core)")
      ->check(CLI::Range(1, 256));
  cmd->add_option("--firmware", scenario.firmware,
                  "run the controllers' real firmware (DIR/mu0..mu8.elf, make firmware) in simavr "
                  "instead of the emulation")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--physics-step-ms", scenario.physics_step_ms,
                  "MuJoCo's time step in ms (default: the simulator's, BENCHMARKS.md); the "
                  "controllers and the bus keep their own timing")
      ->check(finite_range(0.25, 5.0));
}

void add_soak_and_replay(CLI::App& cli, Commands& c) {
  c.soak_cmd = add_soak_command(cli, c.soak);
  c.slope_sweep_cmd = add_slope_sweep_command(cli, c.slope_sweep);
  c.slope_sweep_cmd->add_option("--seed", c.slope_sweep.seed, "the rover unit (default 1)")
      ->check(kSeed);
  c.replay_cmd = cli.add_subcommand(
      "replay", "re-run the driver over a recording and compare every request, bit for bit");
  c.replay_cmd->add_option("DIR", c.replay_dir, "a scenario's --out folder")->required();
  c.export_cmd = cli.add_subcommand(
      "export-mcap", "write DIR/recording.mcap from a recording (the driver re-run over it)");
  c.export_cmd->add_option("DIR", c.export_dir, "a recording: scenario --out, run/drive --record")
      ->required();
  c.export_cmd->add_flag("--force", c.export_force, "write over an existing recording.mcap");
}

void add_live_commands(CLI::App& cli, Commands& c) {
  runner::RunArgs& run = c.run;
  CLI::App* run_cmd = c.run_cmd = cli.add_subcommand(
      "run", "the simulated rover and the driver in real time, with the console (the default)");
  add_console_options(run_cmd, run.console);
  run_cmd->add_option("--scenario", run.scenario, "terrain and faults from a scenario file")
      ->check(CLI::ExistingFile);
  run_cmd->add_option("--seed", run.seed, "the simulator's seed")->check(kSeed);
  run_cmd->add_option("--duration", run.duration_s, "stop after this many seconds (default: on Ctrl-C)")
      ->check(finite_non_negative());
  run_cmd->add_option("--record", run.record,
                      "write can.log, operator.jsonl, telemetry.csv and recording.mcap here");
  run_cmd->add_flag("--quiet", run.quiet, "no status line in the terminal");

  runner::SimArgs& sim = c.sim;
  CLI::App* sim_cmd = c.sim_cmd =
      cli.add_subcommand("sim", "the simulated rover alone, served over socketcand");
  sim_cmd->add_option("--listen", sim.listen, "ADDR:PORT (default 127.0.0.1:29536)");
  sim_cmd->add_option("--channel", sim.channel, "the bus' channel name (default can0)");
  sim_cmd->add_option("--scenario", sim.scenario, "terrain and faults from a scenario file")
      ->check(CLI::ExistingFile);
  sim_cmd->add_option("--seed", sim.seed, "the simulator's seed")->check(kSeed);
  sim_cmd->add_option("--duration", sim.duration_s, "stop after this many seconds")
      ->check(finite_non_negative());
  sim_cmd->add_option("--firmware", sim.firmware,
                      "run the controllers' real firmware (DIR/mu0..mu8.elf, make firmware) in "
                      "simavr instead of the emulation")
      ->check(CLI::ExistingDirectory);

  runner::DriveArgs& drive = c.drive;
  CLI::App* drive_cmd = c.drive_cmd =
      cli.add_subcommand("drive", "the driver on a real or remote bus, with the console");
  drive_cmd->add_option("--can", drive.can, "socketcan:can0 or socketcand://HOST:PORT/CHANNEL")
      ->required();
  add_console_options(drive_cmd, drive.console);
  drive_cmd->add_option("--duration", drive.duration_s, "stop after this many seconds")
      ->check(finite_non_negative());
  drive_cmd->add_flag("--quiet", drive.quiet, "no status line in the terminal");
  drive_cmd->add_option("--record", drive.record,
                        "write can.log, operator.jsonl, telemetry.csv and recording.mcap here");
  drive_cmd->add_option("--joint-memory", drive.joint_memory,
                        "keep the joints' state in FILE, so that a driver restarted after a "
                        "brown-out continues from it instead of taking the joints vertical");
}

void add_calibrate_command(CLI::App& cli, Commands& c) {
  CalibrateArgs& calibrate = c.calibrate;
  CLI::App* cmd = c.calibrate_cmd = cli.add_subcommand(
      "calibrate", "run a calibration procedure of the thesis and write the calibration file");
  cmd->add_option("PROCEDURE", calibrate.procedure,
                  "accelerometer, tilt, voltage, joints, motor-curve, motor-scale, response, "
                  "load, load-gain, spin or voltage-drop (--list describes them)");
  cmd->add_flag("--list", calibrate.list, "name the procedures");
  cmd->add_flag("--sim", calibrate.sim, "on the simulated rover (a laboratory bench)");
  cmd->add_option("--can", calibrate.can,
                  "on a real or remote bus: socketcan:can0 or socketcand://HOST:PORT/CHANNEL");
  cmd->add_option("--out", calibrate.out, "the calibration file (default calibration.toml)");
  cmd->add_flag("--force", calibrate.force,
                "update an existing calibration file (other procedures' values are kept)");
  cmd->add_option("--plot", calibrate.plot, "write the measured data and plots here");
  cmd->add_option("--seed", calibrate.seed, "the simulated unit (--sim)")->check(kSeed);
  cmd->add_option("--ground", calibrate.ground,
                  "the simulated ground (--sim): hard (default), sand, grass, "
                  "lunar-soil");
  cmd->add_option("--duration", calibrate.duration_s,
                  "how long to measure [s] (motor-scale, response, voltage)")
      ->check(finite_positive());
  cmd->add_option("--icr", calibrate.icr, "the PWM period register (motor-curve, load, load-gain)")
      ->check(CLI::Range(255, 2047));
  cmd->add_option("--from", calibrate.from,
                  "voltage-drop: a scenario's --out folder with telemetry.csv")
      ->check(CLI::ExistingDirectory);
}

// The configuration, and the calibration file on top for the driver (--calibration, else
// $MARSOKHOD_CALIBRATION). 0, or kUsageError with one line on `err`.
int load_config(const std::string& config_file, std::string calibration_file,
                config::LoadedConfig& loaded, std::ostream& err) {
  const auto config_path = find_config(config_file);
  if (!config_path) {
    err << "marsokhod: no configuration file: pass --config FILE or set MARSOKHOD_CONFIG\n";
    return kUsageError;
  }
  loaded.config_file = *config_path;
  if (calibration_file.empty()) {
    if (const char* env = std::getenv("MARSOKHOD_CALIBRATION"); env != nullptr && *env != '\0') {
      calibration_file = env;
    }
  }
  try {
    const config::Configuration nominal = config::load_configuration(*config_path);
    loaded.nominal = nominal.params;
    loaded.params = nominal.params;
    loaded.console = nominal.console;
    if (!calibration_file.empty()) {
      loaded.calibration_file = calibration_file;
      const config::Configuration calibrated =
          config::load_configuration(*config_path, calibration_file);
      loaded.params = calibrated.params;
      loaded.calibration = calibrated.calibration;
    }
  } catch (const config::ConfigError& e) {
    err << "marsokhod: " << e.what() << "\n";
    return kUsageError;
  }
  return 0;
}

int run_scenario(Commands& c, const config::LoadedConfig& loaded, std::ostream& out,
                 std::ostream& err) {
  ScenarioArgs& scenario = c.scenario;
  const bool seed_given = c.scenario_seed_option->count() > 0;
  if (seed_given) scenario.seed = c.scenario_seed;
  if (seed_given && (scenario.all || !scenario.seeds.empty())) {
    err << "marsokhod scenario: --seed names one run; a sweep takes --seeds A-B\n";
    return kUsageError;
  }
  std::error_code ec;
  scenario.program = std::filesystem::read_symlink("/proc/self/exe", ec).string();
  scenario.progress = &err == &std::cerr && ::isatty(2) == 1;
  return run_scenario_command(scenario, loaded, out, err);
}

int dispatch(Commands& c, const config::LoadedConfig& loaded, std::istream& in,
             std::ostream& out, std::ostream& err) {
  const Params& params = loaded.params;
  if (c.decode_cmd->parsed()) return run_decode(c.decode, params, in, out, err);
  if (c.scenario_cmd->parsed()) return run_scenario(c, loaded, out, err);
  if (c.soak_cmd->parsed()) return run_soak_command(c.soak, loaded, out, err);
  if (c.slope_sweep_cmd->parsed()) {
    return run_slope_sweep_command(c.slope_sweep, loaded, out, err);
  }
  if (c.calibrate_cmd->parsed()) return run_calibrate_command(c.calibrate, loaded, in, out, err);
  if (c.urdf_cmd->parsed()) {
    try {
      out << sim::rover_urdf(loaded.nominal);
    } catch (const std::exception& e) {
      err << "marsokhod urdf: " << e.what() << "\n";
      return kUsageError;
    }
    return 0;
  }
  if (c.export_cmd->parsed()) {
    return run_export_mcap_command(c.export_dir, c.export_force, params, out, err);
  }
  if (c.replay_cmd->parsed()) return run_replay_command(c.replay_dir, params, out, err);
  if (c.run_cmd->parsed()) {
    c.run.console.web = find_web_dist(c.run.console.web);
    return runner::run_live(c.run, loaded, out, err);
  }
  if (c.sim_cmd->parsed()) return runner::run_sim(c.sim, loaded.nominal, out, err);
  if (c.drive_cmd->parsed()) {
    c.drive.console.web = find_web_dist(c.drive.console.web);
    return runner::run_drive(c.drive, loaded, out, err);
  }
  return kUsageError;
}

}  // namespace

int run_cli(int argc, const char* const* argv, std::istream& in, std::ostream& out,
            std::ostream& err) {
  CLI::App cli{"marsokhod: control stack and simulator for the Marsokhod rover", "marsokhod"};
  cli.require_subcommand(1);
  std::string config_file;
  cli.add_option("--config", config_file,
                 "configuration file (default: $MARSOKHOD_CONFIG, ./config/marsokhod.toml)")
      ->check(CLI::ExistingFile);
  std::string calibration_file;
  cli.add_option("--calibration", calibration_file,
                 "a calibration file (marsokhod calibrate) loaded on top of the configuration "
                 "for the driver (default: $MARSOKHOD_CALIBRATION, else none)")
      ->check(CLI::ExistingFile);
  Commands commands;
  add_offline_commands(cli, commands);
  add_live_commands(cli, commands);
  add_calibrate_command(cli, commands);
  add_soak_and_replay(cli, commands);

  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    out << cli.help();
    return 0;
  } catch (const CLI::CallForAllHelp& e) {
    out << cli.help("", CLI::AppFormatMode::All);
    return 0;
  } catch (const CLI::ParseError& e) {
    err << "marsokhod: " << e.what() << " (see marsokhod --help)\n";
    return kUsageError;
  }
  config::LoadedConfig loaded;
  if (const int status = load_config(config_file, calibration_file, loaded, err); status != 0) {
    return status;
  }
  return dispatch(commands, loaded, in, out, err);
}

}  // namespace marsokhod::app
