#include "runner/sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "runner/child_processes.hpp"
#include "runner/scenario_runner.hpp"

namespace marsokhod::runner {
namespace {

TEST(SeedRange, ParsesARangeAndASingleSeed) {
  const SeedRange r = parse_seed_range("1-20");
  EXPECT_EQ(r.first, 1u);
  EXPECT_EQ(r.last, 20u);
  EXPECT_EQ(r.count(), 20u);
  const SeedRange one = parse_seed_range("7");
  EXPECT_EQ(one.first, 7u);
  EXPECT_EQ(one.last, 7u);
  EXPECT_EQ(parse_seed_range("0-0").count(), 1u);
}

TEST(SeedRange, RejectsWhatIsNotARange) {
  for (const char* bad : {"", "-3", "1-", "a-b", "1-2-3", "1.5", " 1", "2-1", "99999999999999999999",
                          "0-100000"}) {
    EXPECT_THROW(parse_seed_range(bad), std::invalid_argument) << bad;
  }
  try {
    parse_seed_range("5-2");
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "--seeds: '5-2': the first seed is larger than the last");
  }
}

SweepCheck check(const char* name, std::optional<double> value, std::optional<double> min,
                 std::optional<double> max) {
  SweepCheck c{name, false, value, min, max, ""};
  c.passed = value && (!min || *value >= *min) && (!max || *value <= *max);
  return c;
}

TEST(Sweep, ExcessIsTheDistanceOutsideTheLimits) {
  EXPECT_DOUBLE_EQ(check_excess(check("a", 0.5, 0.0, 1.0)), 0.0);
  EXPECT_DOUBLE_EQ(check_excess(check("a", 1.25, 0.0, 1.0)), 0.25);
  EXPECT_DOUBLE_EQ(check_excess(check("a", -2.0, 0.0, std::nullopt)), 2.0);
  EXPECT_TRUE(std::isinf(check_excess(check("a", std::nullopt, 0.0, 1.0))));
}

TEST(Sweep, TableCountsPassesAndKeepsTheWorstValueWithItsSeed) {
  std::vector<SweepRun> runs;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    SweepRun r{"joints", seed, true, "", 10.0, 1.0, {}};
    // The bound is passed on seeds 2 (by 0.02) and 3 (by 0.04): the worst is seed 3's.
    const double excess = seed == 2 ? 0.02 : seed == 3 ? 0.04 : 0.0;
    r.checks.push_back(check("bounds", excess, std::nullopt, 0.01));
    r.checks.push_back(check("reached", 1.0, 0.5, std::nullopt));
    r.passed = r.checks[0].passed && r.checks[1].passed;
    runs.push_back(r);
  }
  runs.push_back(failed_run("spin", 9, "ended by signal 11"));
  runs.push_back(SweepRun{"spin", 10, true, "", 5.0, 1.0, {check("yaw", 2.0, 1.0, 3.0)}});
  const SweepSummary s = summarize(runs);
  EXPECT_EQ(s.runs, 6);
  EXPECT_EQ(s.passed, 3);
  EXPECT_FALSE(s.all_passed());
  EXPECT_DOUBLE_EQ(s.sim_time_s, 45.0);
  ASSERT_EQ(s.scenarios.size(), 2u);
  const ScenarioSweep& joints = s.scenarios[0];
  EXPECT_EQ(joints.scenario, "joints");
  EXPECT_EQ(joints.passed, 2);
  EXPECT_EQ(joints.failed_seeds, (std::vector<std::uint64_t>{2, 3}));
  ASSERT_EQ(joints.failing_checks.size(), 1u);
  EXPECT_EQ(joints.failing_checks[0].name, "bounds");
  EXPECT_EQ(joints.failing_checks[0].failures, 2);
  EXPECT_EQ(joints.failing_checks[0].worst_seed, 3u);
  EXPECT_DOUBLE_EQ(*joints.failing_checks[0].worst_value, 0.04);
  const ScenarioSweep& spin = s.scenarios[1];
  EXPECT_EQ(spin.passed, 1);
  ASSERT_EQ(spin.errors.size(), 1u);
  EXPECT_EQ(spin.errors[0], "seed 9: ended by signal 11");
  const std::string text = to_text(s);
  EXPECT_NE(text.find("bounds: 2× failed, worst 0.04"), std::string::npos) << text;
  EXPECT_NE(text.find("on seed 3"), std::string::npos) << text;
  EXPECT_NE(text.find("3 of 6 runs passed"), std::string::npos) << text;
  const auto j = to_json(s);
  EXPECT_EQ(j["scenarios"][0]["failing_checks"][0]["worst_seed"], 3);
  EXPECT_FALSE(j["all_passed"].get<bool>());
}

TEST(Sweep, MarginIsTheSignedDistanceToTheNearerLimit) {
  EXPECT_DOUBLE_EQ(check_margin(check("a", 0.75, 0.0, 1.0)), 0.25);
  EXPECT_DOUBLE_EQ(check_margin(check("a", 0.1, 0.0, 1.0)), 0.1);
  EXPECT_DOUBLE_EQ(check_margin(check("a", 1.25, 0.0, 1.0)), -0.25);
  EXPECT_DOUBLE_EQ(check_margin(check("a", 3.0, 1.0, std::nullopt)), 2.0);
  EXPECT_TRUE(std::isinf(check_margin(check("a", std::nullopt, 0.0, 1.0))));
  EXPECT_LT(check_margin(check("a", std::nullopt, 0.0, 1.0)), 0.0);
}

TEST(Sweep, EveryCheckKeepsItsTightestRunPassedOrNot) {
  // A drop check (≤ 1.8) passing on every seed: 1.70, 1.78, 1.75 — the tightest is seed 2's
  // 1.78, 0.02 inside; the speed check (≥ 0.5) is tightest on seed 3 (0.6).
  std::vector<SweepRun> runs;
  const double drops[] = {1.70, 1.78, 1.75};
  const double speeds[] = {0.9, 0.7, 0.6};
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    runs.push_back(SweepRun{"pm", seed, true, "", 20.0, 1.0,
                            {check("drop", drops[seed - 1], std::nullopt, 1.8),
                             check("speed", speeds[seed - 1], 0.5, std::nullopt)}});
  }
  const SweepSummary s = summarize(runs);
  ASSERT_EQ(s.scenarios.size(), 1u);
  const auto& margins = s.scenarios[0].margins;
  ASSERT_EQ(margins.size(), 2u);
  EXPECT_EQ(margins[0].name, "drop");
  EXPECT_EQ(margins[0].seed, 2u);
  EXPECT_DOUBLE_EQ(*margins[0].value, 1.78);
  EXPECT_NEAR(margins[0].margin, 0.02, 1e-12);
  EXPECT_EQ(margins[1].name, "speed");
  EXPECT_EQ(margins[1].seed, 3u);
  EXPECT_NEAR(margins[1].margin, 0.1, 1e-12);
  const auto j = to_json(s);
  EXPECT_EQ(j["scenarios"][0]["margins"][0]["seed"], 2);
  EXPECT_NEAR(j["scenarios"][0]["margins"][0]["margin"].get<double>(), 0.02, 1e-12);
}

TEST(Sweep, ARunComesBackFromTheScenarioCommandsJson) {
  ScenarioResult result;
  result.scenario = "dead-man";
  result.seed = 12;
  result.sim_time_s = 9.0;
  result.checks.push_back({"stops", "time_s", false, 0.75, "<= 0.6", std::nullopt, 0.6});
  result.checks.push_back({"gone", "x", false, std::nan(""), ">= 1 (no such metric in this run)", 1.0,
                           std::nullopt});
  result.passed = false;
  const SweepRun run = sweep_run_from_json(nlohmann::json::parse(to_json(result).dump()));
  EXPECT_EQ(run.scenario, "dead-man");
  EXPECT_EQ(run.seed, 12u);
  EXPECT_FALSE(run.passed);
  ASSERT_EQ(run.checks.size(), 2u);
  EXPECT_DOUBLE_EQ(*run.checks[0].value, 0.75);
  EXPECT_FALSE(run.checks[0].min.has_value());
  EXPECT_DOUBLE_EQ(*run.checks[0].max, 0.6);
  EXPECT_DOUBLE_EQ(check_excess(run.checks[0]), 0.75 - 0.6);
  EXPECT_FALSE(run.checks[1].value.has_value());
  EXPECT_THROW(sweep_run_from_json(nlohmann::json::parse(R"({"scenario":"x"})")),
               std::invalid_argument);
}

TEST(ChildProcesses, CollectOutputExitStatusAndSignalInTheGivenOrder) {
  std::vector<std::vector<std::string>> jobs;
  for (int i = 0; i < 5; ++i) {
    jobs.push_back({"/bin/sh", "-c", "echo out" + std::to_string(i) + "; echo err >&2; exit " +
                                         std::to_string(i)});
  }
  jobs.push_back({"/bin/sh", "-c", "kill -9 $$"});
  jobs.push_back({"/nonexistent/program"});
  std::size_t calls = 0;
  const auto outcomes = run_children(jobs, 2, [&calls](std::size_t, const ChildOutcome&) { ++calls; });
  EXPECT_EQ(calls, jobs.size());
  ASSERT_EQ(outcomes.size(), jobs.size());
  for (int i = 0; i < 5; ++i) {
    EXPECT_TRUE(outcomes[i].exited_cleanly());
    EXPECT_EQ(outcomes[i].exit_status, i);
    EXPECT_EQ(outcomes[i].out, "out" + std::to_string(i) + "\n");
    EXPECT_EQ(outcomes[i].err, "err\n");
  }
  EXPECT_EQ(outcomes[5].signal, 9);
  EXPECT_FALSE(outcomes[5].exited_cleanly());
  EXPECT_FALSE(outcomes[6].started);
  EXPECT_NE(outcomes[6].err.find("cannot start '/nonexistent/program'"), std::string::npos);
  EXPECT_THROW(run_children(jobs, 0), std::invalid_argument);
}

TEST(ChildProcesses, ALargeOutputIsReadWhileTheChildRuns) {
  // 1 MB through the pipe: more than its buffer, so the child blocks unless we read as it writes.
  const auto outcomes = run_children({{"/bin/sh", "-c", "head -c 1000000 /dev/zero"}}, 1);
  EXPECT_EQ(outcomes[0].out.size(), 1000000u);
  EXPECT_EQ(outcomes[0].exit_status, 0);
}

}  // namespace
}  // namespace marsokhod::runner
