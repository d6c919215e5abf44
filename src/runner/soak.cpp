#include "runner/soak.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "runner/soak_segment.hpp"

namespace marsokhod::runner {
namespace {

constexpr const char* kWindowFile = "soak.json";

struct Tally {
  SoakResult& result;
  const ViolationReport& report;
  std::optional<std::pair<SegmentPlan, Violation>> first;

  void add(const SegmentPlan& plan, const Violation& v) {
    const auto k = static_cast<std::size_t>(v.invariant);
    if (result.violations[k]++ > 0) return;
    const SoakViolation found{v, plan.index, plan.sand,
                              static_cast<double>(plan.start_us + v.time_us) * 1e-6};
    result.first_violations.push_back(found);
    if (report) report(found);
    if (!first) first = {plan, v};
  }
};

void add_segment_stats(const SegmentPlan& plan, const SegmentRunner& run, Session& session,
                       SoakResult& r) {
  r.cycles += session.cycles();
  r.evaluations += run.checker().evaluations();
  r.driver_restarts += session.driver_restarts();
  r.spurious_silent_faults += run.spurious_silent_faults();
  r.missions_reached += run.missions_reached();
  r.missions_aborted += run.missions_aborted();
  if (const auto& at = run.checker().max_joint_excess_at();
      at && run.checker().max_joint_excess_rad() > r.max_joint_excess_rad) {
    r.max_joint_excess_at = SoakViolation{*at, plan.index, plan.sand,
                                          static_cast<double>(plan.start_us + at->time_us) * 1e-6};
  }
  r.max_joint_excess_rad = std::max(r.max_joint_excess_rad, run.checker().max_joint_excess_rad());
  r.max_unknown_joint_excess_rad =
      std::max(r.max_unknown_joint_excess_rad, run.checker().max_unknown_joint_excess_rad());
  r.max_down_joint_excess_rad =
      std::max(r.max_down_joint_excess_rad, run.checker().max_down_joint_excess_rad());
  for (std::size_t k = 0; k < kFaultKindCount; ++k) {
    r.faults_injected[k] += run.faults().injected()[k];
    r.fault_active_s[k] += run.faults().active_s()[k];
  }
  const OperatorStats& s = run.script().stats();
  OperatorStats& t = r.operator_stats;
  for (std::size_t a = 0; a < kActivityCount; ++a) t.activities[a] += s.activities[a];
  t.commands += s.commands;
  t.short_silences += s.short_silences;
  t.long_silences += s.long_silences;
  t.hand_overs += s.hand_overs;
  t.fault_clears += s.fault_clears;
  t.heartbeats += s.heartbeats;
}

// A violation (or the worst joint excess) in the summary: where in the soak, and what.
nlohmann::ordered_json violation_json(const SoakViolation& v, bool with_invariant) {
  nlohmann::ordered_json j;
  if (with_invariant) j["invariant"] = invariant_name(v.violation.invariant);
  j["soak_time_s"] = v.soak_time_s;
  j["segment"] = v.segment;
  j["terrain"] = v.sand ? "sand" : "hard";
  j["session_time_s"] = static_cast<double>(v.violation.time_us) * 1e-6;
  j["detail"] = v.violation.detail;
  return j;
}

nlohmann::ordered_json window_json(const SoakOptions& options, const SegmentPlan& plan,
                                   std::int64_t start_us, const Violation& v) {
  return {{"soak_seed", options.seed},
          {"hours", options.hours},
          {"segment", plan.index},
          {"segment_seed", plan.seed},
          {"sand", plan.sand},
          {"segment_start_us", plan.start_us},
          {"segment_duration_us", plan.duration_us},
          {"window_start_us", start_us},
          {"violation_time_us", v.time_us},
          {"invariant", invariant_name(v.invariant)},
          {"detail", v.detail}};
}

// Runs the violation's segment again, recording from window_s before the violation to it, and
// checks that the same violation comes back at the same cycle (the run is deterministic).
void write_window(const Params& params, const SoakOptions& options, const SegmentPlan& plan,
                  const Violation& v, SoakResult& result) {
  const Params& rover = options.rover_params != nullptr ? *options.rover_params : params;
  SegmentRunner run(plan, params, rover, options.limits);
  const std::int64_t cycle_us = run.session().cycle_us();
  const std::int64_t window_cycles = std::llround(options.window_s * 1e6) / cycle_us;
  const std::int64_t start_us = std::max<std::int64_t>(0, v.time_us - window_cycles * cycle_us);
  Recorder recorder(options.out, options.config_file, options.calibration_file);
  bool again = false;
  while (run.time_us() <= v.time_us) {
    const bool recording = run.time_us() >= start_us;
    const auto found = run.step(recording ? &recorder : nullptr, run.time_us() == start_us);
    for (const Violation& w : found) again = again || (w.invariant == v.invariant && w.time_us == v.time_us);
  }
  std::ofstream(options.out / kWindowFile) << window_json(options, plan, start_us, v).dump(2) << '\n';
  result.recording = options.out;
  if (!again) result.recording_note = "the re-run did not find the violation again: not deterministic";
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

std::uint64_t SoakResult::total_violations() const {
  std::uint64_t n = 0;
  for (std::uint64_t v : violations) n += v;
  return n;
}

SoakResult run_soak(const Params& params, const SoakOptions& options,
                    const ViolationReport& report) {
  if (!(options.hours > 0.0) || !std::isfinite(options.hours)) {
    throw std::invalid_argument("hours must be a positive number of simulated hours");
  }
  const Params& rover = options.rover_params != nullptr ? *options.rover_params : params;
  SoakResult result;
  result.seed = options.seed;
  Tally tally{result, report, std::nullopt};
  const auto wall_start = std::chrono::steady_clock::now();
  const auto plans = plan_segments(options.hours, options.seed, options.segment_s,
                                   params.cycle.period_s);
  std::int64_t simulated_us = 0;
  for (const SegmentPlan& plan : plans) {
    SegmentRunner run(plan, params, rover, options.limits);
    while (!run.done()) {
      for (const Violation& v : run.step()) tally.add(plan, v);
    }
    add_segment_stats(plan, run, run.session(), result);
    simulated_us += run.time_us();
  }
  result.segments = plans.size();
  result.sim_hours = static_cast<double>(simulated_us) * 1e-6 / 3600.0;
  result.wall_time_s = seconds_since(wall_start);
  result.real_time_factor =
      result.wall_time_s > 0.0 ? result.sim_hours * 3600.0 / result.wall_time_s : 0.0;
  if (tally.first && !options.out.empty()) {
    write_window(params, options, tally.first->first, tally.first->second, result);
  } else if (tally.first) {
    result.recording_note = "no recording: no output folder";
  }
  return result;
}

nlohmann::ordered_json to_json(const SoakResult& r) {
  nlohmann::ordered_json j;
  j["seed"] = r.seed;
  j["sim_hours"] = r.sim_hours;
  j["wall_time_s"] = r.wall_time_s;
  j["real_time_factor"] = r.real_time_factor;
  j["segments"] = r.segments;
  j["cycles"] = r.cycles;
  j["invariants_checked"] = r.evaluations;
  j["driver_restarts"] = r.driver_restarts;
  j["spurious_silent_faults"] = r.spurious_silent_faults;
  j["max_joint_excess_rad"] = r.max_joint_excess_rad;
  j["max_unknown_joint_excess_rad"] = r.max_unknown_joint_excess_rad;
  j["max_down_joint_excess_rad"] = r.max_down_joint_excess_rad;
  if (r.max_joint_excess_at) {
    j["max_joint_excess_at"] = violation_json(*r.max_joint_excess_at, false);
  }
  for (std::size_t k = 0; k < kFaultKindCount; ++k) {
    const char* name = fault_kind_name(static_cast<FaultKind>(k));
    j["faults_injected"][name] = r.faults_injected[k];
    j["fault_active_s"][name] = r.fault_active_s[k];
  }
  const OperatorStats& o = r.operator_stats;
  j["operator"] = {{"commands", o.commands},       {"short_silences", o.short_silences},
                   {"long_silences", o.long_silences}, {"hand_overs", o.hand_overs},
                   {"fault_clears", o.fault_clears}, {"heartbeats", o.heartbeats},
                   {"missions_reached", r.missions_reached},
                   {"missions_aborted", r.missions_aborted}};
  for (std::size_t a = 0; a < kActivityCount; ++a) {
    j["operator"]["activities"][activity_name(static_cast<Activity>(a))] = o.activities[a];
  }
  for (std::size_t k = 0; k < kInvariantCount; ++k) {
    j["violations"][invariant_name(static_cast<Invariant>(k))] = r.violations[k];
  }
  j["first_violations"] = nlohmann::ordered_json::array();
  for (const SoakViolation& v : r.first_violations) {
    j["first_violations"].push_back(violation_json(v, true));
  }
  j["recording"] = r.recording ? nlohmann::ordered_json(r.recording->string()) : nullptr;
  if (!r.recording_note.empty()) j["recording_note"] = r.recording_note;
  j["passed"] = r.total_violations() == 0;
  return j;
}

std::unique_ptr<driver::Driver> soak_window_driver(const std::filesystem::path& folder,
                                                   const Params& driver_params,
                                                   const Params& rover_params) {
  const auto file = folder / kWindowFile;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return nullptr;
  std::ifstream in(file);
  SegmentPlan plan;
  std::int64_t start_us = 0;
  try {
    const auto j = nlohmann::json::parse(in);
    plan.index = j.at("segment").get<std::size_t>();
    plan.seed = j.at("segment_seed").get<std::uint64_t>();
    plan.sand = j.at("sand").get<bool>();
    plan.start_us = j.at("segment_start_us").get<std::int64_t>();
    plan.duration_us = j.at("segment_duration_us").get<std::int64_t>();
    start_us = j.at("window_start_us").get<std::int64_t>();
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(file.string() + ": " + e.what());
  }
  SegmentRunner run(plan, driver_params, rover_params, CheckerLimits{});
  while (run.time_us() < start_us) run.step();
  return run.session().take_driver();
}

}  // namespace marsokhod::runner
