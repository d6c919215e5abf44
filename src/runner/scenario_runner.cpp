#include "runner/scenario_runner.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include "runner/metrics.hpp"
#include "link/command_json.hpp"
#include "runner/recorder.hpp"
#include "runner/session.hpp"

namespace marsokhod::runner {
namespace {

std::string number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

}  // namespace

void apply_fault(const FaultEvent& f, Session& session) {
  sim::SimulatedRover& rover = session.rover();
  sim::SimFaults faults = f.clear ? sim::SimFaults{} : rover.faults();
  for (std::size_t w : f.wheel_blocked) faults.wheel_blocked[w] = true;
  for (std::size_t j : f.joint_jammed) faults.joint_jammed[j] = true;
  for (std::size_t w : f.wheel_no_contact) faults.wheel_no_contact[w] = true;
  for (std::size_t c : f.silent) faults.silent[c] = true;
  if (f.frame_loss) faults.frame_loss_probability = *f.frame_loss;
  if (f.lost_pulses) faults.lost_pulse_fraction[f.lost_pulses->first] = f.lost_pulses->second;
  if (f.battery_sag_ohm) faults.extra_series_resistance_ohm = *f.battery_sag_ohm;
  rover.set_faults(faults);
  if (f.brownout) rover.force_brownout();
  if (f.driver_halt) session.halt_driver();
}

namespace {

CheckResult evaluate(const Check& c, const std::map<std::string, double>& metrics) {
  CheckResult r{c.name, c.metric, false, std::nan(""), "", c.min, c.max};
  if (c.min && c.max) r.limit = "[" + number(*c.min) + ", " + number(*c.max) + "]";
  else if (c.min) r.limit = ">= " + number(*c.min);
  else r.limit = "<= " + number(*c.max);
  const auto value_of = [&metrics](const std::string& name) -> std::optional<double> {
    const auto it = metrics.find(name);
    return it == metrics.end() ? std::nullopt : std::optional(it->second);
  };
  const auto first = value_of(c.ratio_of ? c.ratio_of->first : c.metric);
  const auto second = c.ratio_of ? value_of(c.ratio_of->second) : std::optional(1.0);
  if (!first || !second) {
    r.limit += " (no such metric in this run)";
    return r;
  }
  r.value = c.ratio_of ? *first / *second : *first;
  r.passed = std::isfinite(r.value) && (!c.min || r.value >= *c.min) && (!c.max || r.value <= *c.max);
  return r;
}

// The operator's input for the cycle at `now`: the latest event at or before it.
const InputEvent* current_input(const Scenario& s, double now) {
  const InputEvent* current = nullptr;
  for (const InputEvent& e : s.inputs) {
    if (e.t_s <= now + 1e-9) current = &e;
  }
  return current;
}

// A new [[input]] takes over: a silence starts the stop timing, position targets are what the
// joints are measured against.
void note_new_input(const InputEvent& event, double now, Metrics& metrics) {
  if (!event.input) metrics.mark_stop(now);
  const auto& t = event.input && event.input->targets ? event.input->targets : std::nullopt;
  metrics.set_joint_targets(t ? t->front_joint_target_rad : std::nullopt,
                            t ? t->rear_joint_target_rad : std::nullopt);
}

}  // namespace

ScenarioResult run_scenario(const Scenario& scenario, const Params& params,
                            const RunOptions& options) {
  ScenarioResult result;
  result.scenario = scenario.name;
  result.seed = options.seed.value_or(scenario.seed);
  sim::SimOptions sim = scenario.sim;
  sim.seed = result.seed;
  if (!options.firmware_dir.empty()) sim.firmware_dir = options.firmware_dir;
  if (options.physics_step_s) sim.physics_timestep_s = *options.physics_step_s;
  Session session(options.rover_params != nullptr ? *options.rover_params : params, params, sim);
  if (scenario.state_of_charge) session.rover().set_state_of_charge(*scenario.state_of_charge);
  session.set_runtime(link::runtime_settings_from_json(scenario.runtime, session.runtime()));
  std::unique_ptr<Recorder> recorder;
  if (options.out) {
    recorder = std::make_unique<Recorder>(
        *options.out, options.config_file, options.calibration_file, &params,
        "scenario " + scenario.name + " --seed " + std::to_string(result.seed));
  }
  Metrics metrics(params, scenario.phases);
  std::size_t next_fault = 0, next_runtime = 0;
  const InputEvent* previous = nullptr;
  driver::OperatorInput heartbeat;
  heartbeat.heartbeat = true;
  bool runtime_changed = true;
  const auto wall_start = std::chrono::steady_clock::now();
  while (session.time_s() < scenario.duration_s - 1e-9) {
    const double now = session.time_s();
    while (next_fault < scenario.faults.size() && scenario.faults[next_fault].t_s <= now + 1e-9) {
      const FaultEvent& fault = scenario.faults[next_fault++];
      apply_fault(fault, session);
      if (fault.driver_halt) metrics.mark_stop(now);
    }
    while (next_runtime < scenario.runtime_changes.size() &&
           scenario.runtime_changes[next_runtime].t_s <= now + 1e-9) {
      session.set_runtime(link::runtime_settings_from_json(
          scenario.runtime_changes[next_runtime++].settings, session.runtime()));
      runtime_changed = true;
    }
    const InputEvent* event = current_input(scenario, now);
    const bool repeated = event == previous;
    if (!repeated && event != nullptr) note_new_input(*event, now, metrics);
    previous = event;
    const driver::OperatorInput* input = event && event->input ? &*event->input : nullptr;
    // The operator's input goes again every cycle until the next [[input]]; a mission is asked
    // for once and then kept alive by heartbeats, as the console does.
    if (input != nullptr && input->mission && repeated) input = &heartbeat;
    const CycleRecord& cycle = session.step(input);
    metrics.observe(session, cycle);
    if (recorder) {
      recorder->record(cycle, runtime_changed ? std::optional(session.runtime()) : std::nullopt,
                       session.status(), session.rover());
    }
    runtime_changed = false;
  }
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  result.sim_time_s = session.time_s();
  result.real_time_factor = result.wall_time_s > 0.0 ? result.sim_time_s / result.wall_time_s : 0.0;
  result.metrics = metrics.finish(session);
  result.passed = true;
  for (const Check& c : scenario.checks) result.checks.push_back(evaluate(c, result.metrics));
  for (const CheckResult& c : result.checks) result.passed = result.passed && c.passed;
  if (recorder) recorder->finish();
  recorder.reset();  // flush before plotting
  if (options.out && options.plots) {
    if (auto note = make_plots(*options.out)) result.notes.push_back(*note);
  }
  return result;
}

nlohmann::ordered_json to_json(const ScenarioResult& r) {
  nlohmann::ordered_json j;
  j["scenario"] = r.scenario;
  j["seed"] = r.seed;
  j["sim_time_s"] = r.sim_time_s;
  j["wall_time_s"] = r.wall_time_s;
  j["real_time_factor"] = r.real_time_factor;
  j["metrics"] = nlohmann::ordered_json::object();
  for (const auto& [name, value] : r.metrics) j["metrics"][name] = value;
  j["checks"] = nlohmann::ordered_json::array();
  for (const CheckResult& c : r.checks) {
    j["checks"].push_back({{"name", c.name},
                           {"metric", c.metric},
                           {"passed", c.passed},
                           {"value", std::isfinite(c.value) ? nlohmann::ordered_json(c.value)
                                                            : nlohmann::ordered_json()},
                           {"limit", c.limit},
                           {"min", c.min ? nlohmann::ordered_json(*c.min) : nlohmann::ordered_json()},
                           {"max", c.max ? nlohmann::ordered_json(*c.max) : nlohmann::ordered_json()}});
  }
  j["passed"] = r.passed;
  if (!r.notes.empty()) j["notes"] = r.notes;
  return j;
}

}  // namespace marsokhod::runner
