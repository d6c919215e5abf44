#include "runner/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "runner/child_processes.hpp"

namespace marsokhod::runner {
namespace {

std::uint64_t parse_seed(const std::string& text, const std::string& whole) {
  if (text.empty() || text.size() > 19 ||
      text.find_first_not_of("0123456789") != std::string::npos) {
    throw std::invalid_argument("--seeds: '" + whole +
                                "': seeds are whole numbers ≥ 0, given as A-B or N");
  }
  return std::stoull(text);
}

std::optional<double> optional_number(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  if (it == j.end() || !it->is_number()) return std::nullopt;
  const double v = it->get<double>();
  return std::isfinite(v) ? std::optional(v) : std::nullopt;
}

std::string format_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

void add_failure(FailingCheck& f, const SweepCheck& c, std::uint64_t seed) {
  ++f.failures;
  const double excess = check_excess(c);
  if (f.failures == 1 || excess > f.worst_excess) {
    f.worst_excess = excess;
    f.worst_value = c.value;
    f.worst_seed = seed;
  }
}

}  // namespace

SeedRange parse_seed_range(const std::string& text) {
  const auto dash = text.find('-');
  SeedRange r;
  if (dash == std::string::npos) {
    r.first = r.last = parse_seed(text, text);
  } else {
    r.first = parse_seed(text.substr(0, dash), text);
    r.last = parse_seed(text.substr(dash + 1), text);
  }
  if (r.first > r.last) {
    throw std::invalid_argument("--seeds: '" + text + "': the first seed is larger than the last");
  }
  if (r.last - r.first >= 100000) {
    throw std::invalid_argument("--seeds: '" + text + "': at most 100000 seeds in one sweep");
  }
  return r;
}

SweepRun sweep_run_from_json(const nlohmann::json& j) {
  if (!j.is_object() || !j.contains("scenario") || !j.contains("seed") || !j.contains("passed") ||
      !j.contains("checks") || !j["checks"].is_array()) {
    throw std::invalid_argument("not a scenario result (scenario, seed, passed, checks)");
  }
  SweepRun r;
  r.scenario = j["scenario"].get<std::string>();
  r.seed = j["seed"].get<std::uint64_t>();
  r.passed = j["passed"].get<bool>();
  r.sim_time_s = optional_number(j, "sim_time_s").value_or(0.0);
  r.wall_time_s = optional_number(j, "wall_time_s").value_or(0.0);
  for (const auto& c : j["checks"]) {
    SweepCheck check;
    check.name = c.at("name").get<std::string>();
    check.passed = c.at("passed").get<bool>();
    check.value = optional_number(c, "value");
    check.min = optional_number(c, "min");
    check.max = optional_number(c, "max");
    check.limit = c.value("limit", "");
    r.checks.push_back(std::move(check));
  }
  return r;
}

SweepRun failed_run(const std::string& scenario, std::uint64_t seed, const std::string& error) {
  SweepRun r;
  r.scenario = scenario;
  r.seed = seed;
  r.error = error;
  return r;
}

double check_excess(const SweepCheck& c) {
  if (!c.value) return std::numeric_limits<double>::infinity();
  double excess = 0.0;
  if (c.min) excess = std::max(excess, *c.min - *c.value);
  if (c.max) excess = std::max(excess, *c.value - *c.max);
  return excess;
}

double check_margin(const SweepCheck& c) {
  if (!c.value) return -std::numeric_limits<double>::infinity();
  double margin = std::numeric_limits<double>::infinity();
  if (c.min) margin = std::min(margin, *c.value - *c.min);
  if (c.max) margin = std::min(margin, *c.max - *c.value);
  return margin;
}

namespace {

void add_margin(std::vector<CheckMargin>& margins, const SweepCheck& c, std::uint64_t seed) {
  const double margin = check_margin(c);
  auto m = std::find_if(margins.begin(), margins.end(),
                        [&c](const CheckMargin& x) { return x.name == c.name; });
  if (m == margins.end()) {
    margins.push_back({c.name, c.limit, c.value, seed, margin});
  } else if (margin < m->margin) {
    *m = {c.name, c.limit, c.value, seed, margin};
  }
}

}  // namespace

SweepSummary summarize(const std::vector<SweepRun>& runs) {
  SweepSummary s;
  std::map<std::string, std::size_t> index;
  for (const SweepRun& run : runs) {
    auto [it, added] = index.emplace(run.scenario, s.scenarios.size());
    if (added) {
      ScenarioSweep fresh;
      fresh.scenario = run.scenario;
      s.scenarios.push_back(std::move(fresh));
    }
    ScenarioSweep& sc = s.scenarios[it->second];
    ++sc.runs;
    ++s.runs;
    sc.sim_time_s += run.sim_time_s;
    sc.wall_time_s += run.wall_time_s;
    s.sim_time_s += run.sim_time_s;
    for (const SweepCheck& c : run.checks) add_margin(sc.margins, c, run.seed);
    if (run.passed && run.error.empty()) {
      ++sc.passed;
      ++s.passed;
      continue;
    }
    sc.failed_seeds.push_back(run.seed);
    if (!run.error.empty()) sc.errors.push_back("seed " + std::to_string(run.seed) + ": " + run.error);
    for (const SweepCheck& c : run.checks) {
      if (c.passed) continue;
      auto f = std::find_if(sc.failing_checks.begin(), sc.failing_checks.end(),
                            [&c](const FailingCheck& x) { return x.name == c.name; });
      if (f == sc.failing_checks.end()) {
        FailingCheck fresh;
        fresh.name = c.name;
        fresh.limit = c.limit;
        sc.failing_checks.push_back(std::move(fresh));
        f = sc.failing_checks.end() - 1;
      }
      add_failure(*f, c, run.seed);
    }
  }
  return s;
}

std::string to_text(const SweepSummary& s) {
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line, "%-24s %9s  %s\n", "scenario", "passed", "failing checks (worst value, its seed)");
  out += line;
  for (const ScenarioSweep& sc : s.scenarios) {
    const std::string count = std::to_string(sc.passed) + "/" + std::to_string(sc.runs);
    std::snprintf(line, sizeof line, "%-24s %9s  %s\n", sc.scenario.c_str(), count.c_str(),
                  sc.passed == sc.runs ? "" : (std::to_string(sc.runs - sc.passed) + " failed").c_str());
    out += line;
    for (const FailingCheck& f : sc.failing_checks) {
      const std::string worst = f.worst_value ? format_number(*f.worst_value) : "no value";
      std::snprintf(line, sizeof line, "%-24s %9s    %s: %d× failed, worst %s (limit %s) on seed %llu\n",
                    "", "", f.name.c_str(), f.failures, worst.c_str(), f.limit.c_str(),
                    static_cast<unsigned long long>(f.worst_seed));
      out += line;
    }
    for (const std::string& e : sc.errors) out += std::string(36, ' ') + "error: " + e + "\n";
  }
  std::snprintf(line, sizeof line, "%d of %d runs passed; %.1f s simulated\n", s.passed, s.runs,
                s.sim_time_s);
  out += line;
  return out;
}

nlohmann::ordered_json to_json(const SweepSummary& s) {
  nlohmann::ordered_json j;
  j["runs"] = s.runs;
  j["passed"] = s.passed;
  j["all_passed"] = s.all_passed();
  j["sim_time_s"] = s.sim_time_s;
  j["scenarios"] = nlohmann::ordered_json::array();
  for (const ScenarioSweep& sc : s.scenarios) {
    nlohmann::ordered_json js;
    js["scenario"] = sc.scenario;
    js["runs"] = sc.runs;
    js["passed"] = sc.passed;
    js["failed_seeds"] = sc.failed_seeds;
    js["sim_time_s"] = sc.sim_time_s;
    js["wall_time_s"] = sc.wall_time_s;
    js["failing_checks"] = nlohmann::ordered_json::array();
    for (const FailingCheck& f : sc.failing_checks) {
      js["failing_checks"].push_back(
          {{"name", f.name},
           {"limit", f.limit},
           {"failures", f.failures},
           {"worst_value", f.worst_value ? nlohmann::ordered_json(*f.worst_value) : nlohmann::ordered_json()},
           {"worst_seed", f.worst_seed}});
    }
    js["errors"] = sc.errors;
    js["margins"] = nlohmann::ordered_json::array();
    for (const CheckMargin& m : sc.margins) {
      const bool finite = std::isfinite(m.margin);
      js["margins"].push_back(
          {{"name", m.name},
           {"limit", m.limit},
           {"value", m.value ? nlohmann::ordered_json(*m.value) : nlohmann::ordered_json()},
           {"seed", m.seed},
           {"margin", finite ? nlohmann::ordered_json(m.margin) : nlohmann::ordered_json()}});
    }
    j["scenarios"].push_back(std::move(js));
  }
  return j;
}

}  // namespace marsokhod::runner

namespace marsokhod::runner {
namespace {

SweepRun run_from_outcome(const std::string& scenario, std::uint64_t seed,
                          const ChildOutcome& outcome) {
  const auto last_line = [](const std::string& text) {
    std::string t = text;
    while (!t.empty() && (t.back() == '\n' || t.back() == '\r')) t.pop_back();
    const auto nl = t.rfind('\n');
    return nl == std::string::npos ? t : t.substr(nl + 1);
  };
  if (!outcome.started) return failed_run(scenario, seed, outcome.err);
  if (outcome.signal != 0) {
    return failed_run(scenario, seed, "ended by signal " + std::to_string(outcome.signal) +
                                          (outcome.err.empty() ? "" : ": " + last_line(outcome.err)));
  }
  // Exit 0 (passed) and 1 (a check failed) both print the result; anything else is an error.
  if (outcome.exit_status == 0 || outcome.exit_status == 1) {
    try {
      SweepRun run = sweep_run_from_json(nlohmann::json::parse(outcome.out));
      run.scenario = scenario;
      return run;
    } catch (const std::exception& e) {
      return failed_run(scenario, seed, std::string("unreadable result: ") + e.what());
    }
  }
  return failed_run(scenario, seed, "exit status " + std::to_string(outcome.exit_status) + ": " +
                                        last_line(outcome.err));
}

}  // namespace

std::vector<SweepRun> run_sweep(const SweepPlan& plan,
                                const std::function<void(const SweepProgress&)>& progress) {
  std::vector<std::vector<std::string>> jobs;
  std::vector<std::pair<std::string, std::uint64_t>> what;
  for (const auto& [name, file, own_seed] : plan.scenarios) {
    const SeedRange seeds = plan.seeds.value_or(SeedRange{own_seed, own_seed});
    for (std::uint64_t seed = seeds.first;; ++seed) {
      std::vector<std::string> argv{plan.program};
      argv.insert(argv.end(), plan.common_args.begin(), plan.common_args.end());
      argv.insert(argv.end(), {"scenario", file, "--seed", std::to_string(seed), "--json", "--no-plots"});
      if (!plan.out.empty()) {
        argv.insert(argv.end(), {"--out", plan.out + "/" + name + "-seed-" + std::to_string(seed)});
      }
      if (!plan.firmware_dir.empty()) {
        argv.insert(argv.end(), {"--firmware", plan.firmware_dir});
      }
      if (plan.physics_step_ms) {
        std::ostringstream step;
        step.precision(17);
        step << *plan.physics_step_ms;
        argv.insert(argv.end(), {"--physics-step-ms", step.str()});
      }
      jobs.push_back(std::move(argv));
      what.emplace_back(name, seed);
      if (seed == seeds.last) break;
    }
  }
  std::vector<SweepRun> runs(jobs.size());
  SweepProgress p{0, jobs.size(), 0};
  run_children(jobs, std::max<std::size_t>(plan.jobs, 1),
               [&](std::size_t index, const ChildOutcome& outcome) {
                 runs[index] = run_from_outcome(what[index].first, what[index].second, outcome);
                 ++p.done;
                 if (!runs[index].passed || !runs[index].error.empty()) ++p.failed;
                 if (progress) progress(p);
               });
  return runs;
}

}  // namespace marsokhod::runner
