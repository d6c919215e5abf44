// `marsokhod scenario`: runs a scenario headless, as fast as the machine allows, deterministic
// (the same scenario and seed give the same numbers, bit for bit), and reports its metrics and
// checks. With an output folder it also writes the recording (recorder.hpp) and PNG plots made by
// gnuplot from telemetry.csv (duty cycles and wheel speeds like Figure 3.5; U, Ū and D like
// Figure 6.1; joint positions p̄ and p like Figure 4.11).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/params.hpp"
#include "runner/scenario.hpp"

namespace marsokhod::runner {

struct CheckResult {
  std::string name;
  std::string metric;
  bool passed = false;
  double value = 0.0;
  std::string limit;  // "[1, 3]", "≥ 1", "≤ 3"
  std::optional<double> min, max;
};

struct ScenarioResult {
  std::string scenario;
  std::uint64_t seed = 0;
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;
  double real_time_factor = 0.0;
  std::map<std::string, double> metrics;
  std::vector<CheckResult> checks;
  bool passed = false;
  std::vector<std::string> notes;
};

struct RunOptions {
  std::optional<std::uint64_t> seed;        // overrides the scenario's
  std::optional<std::filesystem::path> out; // the recording and plots
  std::filesystem::path config_file;        // copied into the recording
  // The driver's calibration file (copied into the recording), and the configuration's nominal
  // Params the simulated rover is built from: the unit must not follow the driver's calibration.
  // Without them the rover is built from the driver's Params.
  std::filesystem::path calibration_file;
  const Params* rover_params = nullptr;
  bool plots = true;
  std::string firmware_dir;  // the controllers' real firmware in simavr, or empty: the emulation
  std::optional<double> physics_step_s;  // MuJoCo's step, or unset: the simulator's default
};

class Session;
// Switches a scenario's fault on the running session (the simulator's faults, a brown-out, a
// driver that halts).
void apply_fault(const FaultEvent& fault, Session& session);

ScenarioResult run_scenario(const Scenario& scenario, const Params& params,
                            const RunOptions& options);

nlohmann::ordered_json to_json(const ScenarioResult& result);

// Writes the gnuplot PNGs into `folder` from its telemetry.csv; returns a note if gnuplot is
// missing or failed (the run itself is unaffected).
std::optional<std::string> make_plots(const std::filesystem::path& folder);

}  // namespace marsokhod::runner
