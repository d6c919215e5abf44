#include "app/scenario_command.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <ostream>
#include <algorithm>
#include <cmath>
#include <set>

#include "config/calibration.hpp"
#include "config/load_params.hpp"
#include "runner/export_mcap.hpp"
#include "runner/replay.hpp"
#include "runner/scenario_runner.hpp"
#include "runner/sweep.hpp"
#include "runner/soak.hpp"

namespace marsokhod::app {
namespace {

constexpr int kUsageError = 2;

std::optional<std::filesystem::path> find_scenario(const std::string& name) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(name, ec)) return std::filesystem::path(name);
  for (const auto& folder : scenario_folders()) {
    const auto file = folder / (name + ".toml");
    if (std::filesystem::is_regular_file(file, ec)) return file;
  }
  return std::nullopt;
}

void print_text(const runner::ScenarioResult& r, std::ostream& out) {
  char line[256];
  std::snprintf(line, sizeof line, "scenario %s  seed %llu  %.2f s simulated in %.2f s (%.1f× real time)\n",
                r.scenario.c_str(), static_cast<unsigned long long>(r.seed), r.sim_time_s,
                r.wall_time_s, r.real_time_factor);
  out << line << "metrics:\n";
  for (const auto& [name, value] : r.metrics) {
    std::snprintf(line, sizeof line, "  %-28s %12.4f\n", name.c_str(), value);
    out << line;
  }
  out << "checks:\n";
  for (const auto& c : r.checks) {
    std::snprintf(line, sizeof line, "  %s  %-28s %12.4f  %s\n", c.passed ? "PASS" : "FAIL",
                  c.name.c_str(), c.value, c.limit.c_str());
    out << line;
  }
  for (const auto& note : r.notes) out << "note: " << note << "\n";
  out << (r.passed ? "passed\n" : "FAILED\n");
}

// Every shipped scenario (name, file), the first folder's where names repeat.
std::vector<std::pair<std::string, std::filesystem::path>> all_scenarios() {
  std::vector<std::pair<std::string, std::filesystem::path>> found;
  std::set<std::string> seen;
  for (const auto& folder : scenario_folders()) {
    for (const auto& [name, file] : runner::list_scenarios(folder)) {
      if (seen.insert(name).second) found.emplace_back(name, file);
    }
  }
  std::sort(found.begin(), found.end());
  return found;
}

std::string minutes_and_seconds(double s) {
  char text[32];
  const long total = std::lround(std::max(s, 0.0));
  std::snprintf(text, sizeof text, "%ldm%02lds", total / 60, total % 60);
  return text;
}

}  // namespace

int run_sweep_command(const ScenarioArgs& args, const config::LoadedConfig& config, std::ostream& out,
                      std::ostream& err) {
  runner::SweepPlan plan;
  try {
    if (!args.seeds.empty()) plan.seeds = runner::parse_seed_range(args.seeds);
  } catch (const std::invalid_argument& e) {
    err << "marsokhod scenario: " << e.what() << "\n";
    return kUsageError;
  }
  if (args.all == !args.name.empty()) {
    err << "marsokhod scenario: a sweep takes either a scenario NAME or --all\n";
    return kUsageError;
  }
  std::vector<std::pair<std::string, std::filesystem::path>> chosen;
  if (args.all) {
    chosen = all_scenarios();
  } else if (const auto file = find_scenario(args.name)) {
    chosen.emplace_back(args.name, *file);
  } else {
    err << "marsokhod scenario: no scenario '" << args.name
        << "': not a file, and not in the scenario folders (marsokhod scenario --list)\n";
    return kUsageError;
  }
  for (const auto& [name, file] : chosen) {
    try {
      const runner::Scenario s = runner::load_scenario(file);
      plan.scenarios.push_back({s.name, std::filesystem::absolute(file).string(), s.seed});
    } catch (const std::invalid_argument& e) {
      err << "marsokhod scenario: " << e.what() << "\n";
      return kUsageError;
    }
  }
  plan.program = args.program;
  if (!args.firmware.empty()) plan.firmware_dir = std::filesystem::absolute(args.firmware).string();
  plan.physics_step_ms = args.physics_step_ms;
  plan.common_args = {"--config", std::filesystem::absolute(config.config_file).string()};
  if (!config.calibration_file.empty()) {
    plan.common_args.insert(plan.common_args.end(),
                            {"--calibration", std::filesystem::absolute(config.calibration_file).string()});
  }
  plan.jobs = args.jobs > 0 ? args.jobs : std::max(1u, std::thread::hardware_concurrency());
  plan.out = args.out.empty() ? "" : std::filesystem::absolute(args.out).string();
  const auto start = std::chrono::steady_clock::now();
  const auto show = [&](const runner::SweepProgress& p) {
    if (!args.progress) return;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double left = elapsed / static_cast<double>(p.done) * static_cast<double>(p.total - p.done);
    err << "\rsweep: " << p.done << "/" << p.total << " runs, " << p.failed << " failed, "
        << minutes_and_seconds(left) << " left   " << (p.done == p.total ? "\n" : "") << std::flush;
  };
  const runner::SweepSummary summary = runner::summarize(runner::run_sweep(plan, show));
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (args.json) {
    nlohmann::ordered_json j = runner::to_json(summary);
    j["wall_time_s"] = wall_s;
    j["jobs"] = plan.jobs;
    out << j.dump() << "\n";
  } else {
    out << runner::to_text(summary);
    char line[160];
    std::snprintf(line, sizeof line, "%.1f s wall time with %zu jobs: %.1f× real time\n", wall_s,
                  plan.jobs, wall_s > 0.0 ? summary.sim_time_s / wall_s : 0.0);
    out << line;
  }
  return summary.all_passed() ? 0 : 1;
}

std::vector<std::filesystem::path> scenario_folders() {
  std::vector<std::filesystem::path> folders;
  if (const char* env = std::getenv("MARSOKHOD_SCENARIOS"); env != nullptr && *env != '\0') {
    folders.emplace_back(env);
  }
  folders.emplace_back("scenarios");
  folders.emplace_back(std::filesystem::path(MARSOKHOD_SOURCE_DIR) / "scenarios");
  return folders;
}

int run_scenario_command(const ScenarioArgs& args, const config::LoadedConfig& config, std::ostream& out,
                         std::ostream& err) {
  const Params& params = config.params;
  if (args.list) {
    for (const auto& [name, file] : all_scenarios()) {
      try {
        out << name << "  " << runner::load_scenario(file).description << "\n";
      } catch (const std::exception& e) {
        out << name << "  (invalid: " << e.what() << ")\n";
      }
    }
    return 0;
  }
  if (args.all || !args.seeds.empty()) return run_sweep_command(args, config, out, err);
  if (args.name.empty()) {
    err << "marsokhod scenario: name a scenario or a file (marsokhod scenario --list names them)\n";
    return kUsageError;
  }
  const auto file = find_scenario(args.name);
  if (!file) {
    err << "marsokhod scenario: no scenario '" << args.name
        << "': not a file, and not in the scenario folders (marsokhod scenario --list)\n";
    return kUsageError;
  }
  runner::Scenario scenario;
  try {
    scenario = runner::load_scenario(*file);
  } catch (const std::invalid_argument& e) {
    err << "marsokhod scenario: " << e.what() << "\n";
    return kUsageError;
  }
  runner::RunOptions options;
  options.seed = args.seed;
  if (!args.out.empty()) options.out = args.out;
  options.config_file = config.config_file;
  options.calibration_file = config.calibration_file;
  options.rover_params = &config.nominal;
  options.plots = !args.no_plots;
  options.firmware_dir = args.firmware;
  if (args.physics_step_ms) options.physics_step_s = *args.physics_step_ms / 1000.0;
  runner::ScenarioResult result;
  try {
    result = runner::run_scenario(scenario, params, options);
  } catch (const std::exception& e) {
    err << "marsokhod scenario: " << scenario.name << ": " << e.what() << "\n";
    return kUsageError;
  }
  if (args.json) {
    out << runner::to_json(result).dump() << "\n";
  } else {
    print_text(result, out);
  }
  return result.passed ? 0 : 1;
}

namespace {

// The Params a recording's driver ran with: its config.toml (and calibration.toml on top), else
// `params`; `nominal`: what its simulated rover was built from.
Params recorded_params(const std::filesystem::path& folder, const Params& params, Params& nominal) {
  std::error_code ec;
  Params recorded = params;
  nominal = params;
  const auto config = folder / "config.toml";
  const auto calibration = folder / "calibration.toml";
  if (std::filesystem::is_regular_file(config, ec)) nominal = config::load_params(config);
  if (std::filesystem::is_regular_file(calibration, ec)) {
    recorded = config::load_params(config, calibration);
  } else if (std::filesystem::is_regular_file(config, ec)) {
    recorded = nominal;
  }
  return recorded;
}

}  // namespace

int run_export_mcap_command(const std::string& folder, bool overwrite, const Params& params,
                            std::ostream& out, std::ostream& err) {
  try {
    std::error_code ec;
    if (!std::filesystem::is_directory(folder, ec)) {
      err << "marsokhod export-mcap: '" << folder << "' is not a folder with a recording\n";
      return kUsageError;
    }
    if (!std::filesystem::is_regular_file(std::filesystem::path(folder) / "can.log", ec)) {
      err << "marsokhod export-mcap: '" << folder
          << "' has no can.log: not a recording (scenario --out, run --record, drive --record)\n";
      return kUsageError;
    }
    Params nominal;
    const Params recorded = recorded_params(folder, params, nominal);
    auto start = runner::soak_window_driver(folder, recorded, nominal);
    const runner::ExportResult r = runner::export_mcap(folder, recorded, std::move(start), overwrite);
    out << "wrote " << (std::filesystem::path(folder) / "recording.mcap").string() << ": "
        << r.cycles << " cycles, " << r.messages << " messages"
        << (r.true_pose ? ", /tf from telemetry.csv" : ", no /tf (no true pose in telemetry.csv)")
        << "\n";
    if (!r.identical) {
      out << "the replayed driver differs from the recording from " << r.first_difference
          << " on: its /status, /imu, /joint_states and /pose are the replayed driver's\n";
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    err << "marsokhod export-mcap: " << e.what() << "\n";
    return kUsageError;
  }
}

int run_replay_command(const std::string& folder, const Params& params, std::ostream& out,
                       std::ostream& err) {
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) {
    err << "marsokhod replay: '" << folder << "' is not a folder with a recording\n";
    return kUsageError;
  }
  try {
    Params nominal;  // what a soak's simulated rover was built from
    const Params recorded = recorded_params(folder, params, nominal);
    // A soak's window starts in the middle of a driver's life: the soak is run again to the
    // window's start for that driver (runner/soak.hpp).
    auto start = runner::soak_window_driver(folder, recorded, nominal);
    const runner::ReplayResult r = runner::replay(folder, recorded, std::move(start));
    out << "replayed " << r.cycles << " cycles, compared " << r.frames_compared << " requests: "
        << (r.identical ? "identical to the recording, bit for bit\n" : "DIFFERENT\n");
    if (!r.identical) out << r.first_difference << "\n";
    return r.identical ? 0 : 1;
  } catch (const std::exception& e) {
    err << "marsokhod replay: " << e.what() << "\n";
    return kUsageError;
  }
}

}  // namespace marsokhod::app
