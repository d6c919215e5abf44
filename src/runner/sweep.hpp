// Sweeps: scenarios run once per seed, each seed drawing a different rover unit (the spreads of
// docs/simulator.md), and the table of how they fared: per scenario the runs that passed and, for
// every check that failed on some unit, how often, its worst value and the seed that gave it.
//
// A run is one `marsokhod scenario NAME --seed S --json` (its JSON, scenario_runner.hpp's
// to_json); how the runs are made (child processes, in parallel) is the command's business. The
// worst value of a check is the one furthest outside its limits; a run that could not give a
// value (the metric missing, the run crashed) is worse than any value.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace marsokhod::runner {

struct SeedRange {
  std::uint64_t first = 1;
  std::uint64_t last = 1;
  std::uint64_t count() const { return last - first + 1; }
};

// "A-B" (A ≤ B) or "N"; seeds are whole numbers ≥ 0. Throws std::invalid_argument saying what
// was wrong ("--seeds: '5-2': the first seed is larger than the last").
SeedRange parse_seed_range(const std::string& text);

struct SweepCheck {
  std::string name;
  bool passed = false;
  std::optional<double> value;  // none: the metric was missing or not finite
  std::optional<double> min, max;
  std::string limit;
};

struct SweepRun {
  std::string scenario;
  std::uint64_t seed = 0;
  bool passed = false;
  std::string error;  // a run that ended without a result: why (exit status, signal, stderr)
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;
  std::vector<SweepCheck> checks;
};

// One run from the scenario command's JSON; throws std::invalid_argument if it is not one.
SweepRun sweep_run_from_json(const nlohmann::json& j);
// A run that gave no result: it failed, with the reason.
SweepRun failed_run(const std::string& scenario, std::uint64_t seed, const std::string& error);

// How far `value` lies outside [min, max] (0 inside); +∞ for no value.
double check_excess(const SweepCheck& check);

struct FailingCheck {
  std::string name;
  std::string limit;
  int failures = 0;
  std::optional<double> worst_value;  // none: some run gave no value
  std::uint64_t worst_seed = 0;
  double worst_excess = 0.0;
};

// Every check's tightest run: the value nearest its limits (or furthest outside), over all units.
// margin = the distance to the nearer limit, positive inside, negative outside; a unit that gave
// no value makes it −∞. This is what tells whether a pass holds by a hair.
struct CheckMargin {
  std::string name;
  std::string limit;
  std::optional<double> value;  // none: some run gave no value
  std::uint64_t seed = 0;
  double margin = 0.0;
};

// Signed distance of `value` to the nearer of min, max: > 0 inside, < 0 outside, −∞ for none.
double check_margin(const SweepCheck& check);

struct ScenarioSweep {
  std::string scenario;
  int runs = 0;
  int passed = 0;
  std::vector<std::uint64_t> failed_seeds;
  std::vector<FailingCheck> failing_checks;  // in the order of the scenario's checks
  std::vector<std::string> errors;           // "seed 7: …" for runs without a result
  std::vector<CheckMargin> margins;          // every check, in the order of the scenario's checks
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;  // the runs' own wall time, added up
};

struct SweepSummary {
  std::vector<ScenarioSweep> scenarios;  // in the order their first run was given
  int runs = 0;
  int passed = 0;
  double sim_time_s = 0.0;
  bool all_passed() const { return passed == runs; }
};

SweepSummary summarize(const std::vector<SweepRun>& runs);

// The table: one line a scenario (runs passed), then a line for each failing check.
std::string to_text(const SweepSummary& summary);
nlohmann::ordered_json to_json(const SweepSummary& summary);

}  // namespace marsokhod::runner

namespace marsokhod::runner {

// What a sweep runs: `program [common_args] scenario FILE --seed S --json --no-plots [--out
// out/NAME-seed-S]` for every scenario and seed (each scenario's own seed without `seeds`),
// `jobs` at a time.
struct SweepPlan {
  std::string program;                   // the marsokhod executable
  std::vector<std::string> common_args;  // e.g. --config FILE
  struct Entry {
    std::string name;
    std::string file;
    std::uint64_t own_seed = 1;  // the scenario file's seed, used when `seeds` is not given
  };
  std::vector<Entry> scenarios;
  std::optional<SeedRange> seeds;
  std::size_t jobs = 1;
  std::string out;  // a folder for every run's recording, or empty
  std::string firmware_dir;  // passed on as --firmware: the real firmware in simavr
  std::optional<double> physics_step_ms;  // passed on as --physics-step-ms
};

struct SweepProgress {
  std::size_t done = 0;
  std::size_t total = 0;
  std::size_t failed = 0;
};

// Runs the plan; `progress` is called after each run. The runs come back in the plan's order
// (scenario by scenario, seeds ascending), whatever order they finished in.
std::vector<SweepRun> run_sweep(const SweepPlan& plan,
                                const std::function<void(const SweepProgress&)>& progress = {});

}  // namespace marsokhod::runner
