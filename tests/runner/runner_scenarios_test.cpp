// Every scenario shipped in scenarios/ runs through runner::run_scenario and must pass its checks
// (each a test of its own: ctest -R runner_scenarios_test lists them by name). The limits are in
// the scenario files, each with its reasoning; comparisons across files (the thesis' "advances
// quicker" of chapter 6.3) are here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "runner/scenario.hpp"
#include "runner/scenario_runner.hpp"
#include "runner_test_support.hpp"

namespace marsokhod::runner {
namespace {

using testing::kSourceDir;
using testing::ScratchFolder;
using testing::shipped_params;

std::vector<std::string> shipped_scenarios() {
  std::vector<std::string> names;
  for (const auto& [name, file] : list_scenarios(kSourceDir / "scenarios")) names.push_back(name);
  return names;
}

ScenarioResult run_shipped(const std::string& name) {
  const Scenario scenario = load_scenario(kSourceDir / "scenarios" / (name + ".toml"));
  RunOptions options;
  options.plots = false;
  return run_scenario(scenario, shipped_params(), options);
}

// What a failure shows: every check and every metric, so that the cause is in the CI log.
std::string report(const ScenarioResult& r) {
  std::ostringstream out;
  out << r.scenario << " (seed " << r.seed << ", " << r.sim_time_s << " s simulated in "
      << r.wall_time_s << " s)\nchecks:\n";
  for (const CheckResult& c : r.checks) {
    out << "  " << (c.passed ? "pass " : "FAIL ") << c.name << ": " << c.metric << " = "
        << c.value << ", limit " << c.limit << "\n";
  }
  out << "metrics:\n";
  for (const auto& [name, value] : r.metrics) out << "  " << name << " = " << value << "\n";
  return out.str();
}

// Scenarios whose strict checks fail today for causes outside the scenarios, each analysed and
// left open on the end-to-end issue; their checks are NOT loosened. They are reported as skipped
// (with the reason) until the causes are fixed, then removed from this list. None at present.
const std::map<std::string, std::string> kKnownFailures = {};

class ShippedScenario : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedScenario, PassesItsChecks) {
  if (const auto known = kKnownFailures.find(GetParam()); known != kKnownFailures.end()) {
    GTEST_SKIP() << "known failure, open on the end-to-end issue: " << known->second;
  }
  const ScenarioResult r = run_shipped(GetParam());
  ASSERT_FALSE(r.checks.empty()) << GetParam() << " checks nothing";
  EXPECT_TRUE(r.passed) << report(r);
}

// "rolking-extended-base" → "rolking_extended_base": gtest's names allow no '-'.
std::string test_name(const ::testing::TestParamInfo<std::string>& param) {
  std::string name = param.param;
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(Scenarios, ShippedScenario, ::testing::ValuesIn(shipped_scenarios()),
                         test_name);

TEST(ShippedScenarios, IncludeTheRequiredSet) {
  const std::vector<std::string> names = shipped_scenarios();
  for (const char* required :
       {"straight-and-spin", "joint-positioning", "spin-efficiency", "rolking",
        "front-wheel-walking", "rear-wheel-walking", "worm-like", "rolking-extended-base",
        "slope-slant-on", "slope-slant-off", "power-management-on", "power-management-off",
        "load-distribution-off", "load-distribution-v", "load-distribution-s", "broken-wheel",
        "link-loss", "dead-man",
        // Issue #17: the gaits inside the behaviours' bounds, Field Experiment 6.2 in full.
        "rolking-turning", "rolking-slope-slant-on", "rolking-slope-slant-off",
        "worm-like-slope-slant-on", "worm-like-slope-slant-off",
        "front-wheel-walking-slope-slant-on", "front-wheel-walking-slope-slant-off",
        "rear-wheel-walking-slope-slant-on", "rolking-extended-base-slope-slant-on",
        "rolking-extended-base-slope-slant-off", "broken-center-wheel-turning",
        "tether-current-bound", "tether-no-current-bound",
        "contract-on-turn", "obstacle-axle-placement-on", "obstacle-axle-placement-off",
        // Issue #15: the failsafes that need an estimate, the missions.
        "tip-over", "stuck", "odometry-square-hard", "odometry-square-sand", "waypoint-loop-hard",
        "waypoint-loop-sand", "odometry-rolking",
        // The joint-blocked failsafe (a jammed joint on soft sand).
        "joint-blocked",
        // Issue #14: Field Experiment 5.2, m3 on soft sand; a dune of soft sand (a heightfield).
        "sideways-drift-soft-sand", "sand-dune-crossing"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), required), names.end()) << required;
  }
}

// Field Experiments 6.3/6.4 and chapter 6.2.3: the same front-wheel walk against a block of 0.8
// wheel radii with the axle placement on and off, on a unit the files were not written on (seed 2).
// With it the walk never stalls and keeps going round; without it the front joint pushes the
// front axle into the block until the stuck failsafe stops the rover (on each of seeds 1–20; 0 of
// 20 with it, RELIABILITY.md).
TEST(ShippedScenarios, TheAxlePlacementWalksPastTheStallAtABlock) {
  RunOptions options;
  options.plots = false;
  options.seed = 2;
  const auto run = [&](const std::string& name) {
    return run_scenario(load_scenario(kSourceDir / "scenarios" / (name + ".toml")),
                        shipped_params(), options);
  };
  const ScenarioResult on = run("obstacle-axle-placement-on");
  const ScenarioResult off = run("obstacle-axle-placement-off");
  EXPECT_EQ(on.metrics.at("stuck_faults"), 0.0) << report(on);
  EXPECT_EQ(off.metrics.at("stuck_faults"), 1.0) << report(off);
  EXPECT_GT(on.metrics.at("walk.gait_state_changes"), off.metrics.at("walk.gait_state_changes"))
      << report(on) << report(off);
}

// Chapter 6.3 and Field Experiment 6.6: with h^v (6.5) or h^s (6.6) "Marsokhod appeared to be
// more powerful and to advance quicker" at low v1, and the redistributions "advance with less
// erosion of the soil" (Theses). The comparison runs on the shipped files' 12° slope without their
// brick slab (with it, on the rigid contact sand had before the soil model, all three variants
// stalled where the rear-left wheel met the slab's 2 cm edge, which measured the step, not the
// redistribution). Without the redistribution the rover stalls there, and the stuck failsafe would
// stop it 5 s later and its wheels' slip with it; the comparison is of the traction the
// redistribution gives a rover that keeps trying, so all three run with the failsafe off
// (stuck_time_s = 0). (Until 2026-11-29 it ran on that rigid sand too, where each redistribution
// also made the wheels slip less on average; on the soft sand h^v does on 19 of seeds 1–20 and
// h^s does not, on 18 of them: RELIABILITY.md.)
Params keeps_trying() {
  Params params = shipped_params();
  params.safety.stuck_time_s = 0.0;
  return params;
}

Scenario without_the_slab(const std::string& name) {
  Scenario scenario = load_scenario(kSourceDir / "scenarios" / (name + ".toml"));
  scenario.sim.terrain.obstacles.clear();
  return scenario;
}

// Chapter 6.3 on soft soil (sim/soil's Wong–Reece wheels on the deformable grid): the same climb as
// above, the 12° slope without the slab, on the soil model's `sand`. The erosion is the soil the
// run disturbed (soil_disturbed_m3: the earthwork's cut + fill) per metre the rover climbed. At v1
// = 0.5 rad/s all three stall in the pit they sank into while set down (the load-distribution files
// say why): on seeds 1–20 (2026-12-01) no redistribution climbs 0.052–0.075 m (over 3–16 s, before
// the files' climb ended at 10 s; seed 1 stands still from 4 s on), h^v and h^s climb further on 18
// and 20 of them (0.95–1.27 and 1.02–1.37 of it; on average 0.070 and 0.074 m against 0.064 m),
// "more powerful" as the thesis found. They disturb more soil in all (on average 0.0135 against
// 0.0117 m³), and per metre climbed less on only 6 and 8 of the 20 (on average 0.194 and 0.184
// against 0.184 m³/m): the "less erosion" of chapter 6.3 is not what this soil gives, and is not
// checked. The climb is compared averaged over units 1–8, where one unit's three runs differ by
// about as much as one unit from another (h^v and h^s ahead by 11 % and 17 %). (Until soil laid
// back in a rut lay loose there, 2026-12-01, the rut's raised level propped these slow climbs:
// 0.09–0.14 m, and both redistributions disturbed less per metre on 18–20 units.)
double disturbed_per_metre_climbed(const ScenarioResult& r) {
  return r.metrics.at("soil_disturbed_m3") / r.metrics.at("climb.forward_distance_m");
}

Scenario on_soft_sand(const std::string& name) {
  Scenario scenario = without_the_slab(name);
  scenario.sim.terrain.ground = sim::sand();
  return scenario;
}

TEST(ShippedScenarios, OnSoftSandLoadDistributionClimbsFurther) {
  const Params params = keeps_trying();
  constexpr int kUnits = 8;
  std::map<std::string, double> mean_climb_m;
  for (std::uint64_t seed = 1; seed <= kUnits; ++seed) {
    RunOptions options;
    options.plots = false;
    options.seed = seed;
    for (const char* variant :
         {"load-distribution-off", "load-distribution-v", "load-distribution-s"}) {
      const ScenarioResult r = run_scenario(on_soft_sand(variant), params, options);
      ASSERT_GT(r.metrics.at("climb.forward_distance_m"), 0.0) << report(r);
      mean_climb_m[variant] += r.metrics.at("climb.forward_distance_m") / kUnits;
    }
  }
  for (const char* variant : {"load-distribution-v", "load-distribution-s"}) {
    EXPECT_GT(mean_climb_m[variant], mean_climb_m["load-distribution-off"]) << variant;
  }
}

// Driving against rolking (chapter 5.3) up a slope of soft sand for 27 s, v1 = 1 rad/s against
// rolking at full gait speed ("we compared different wheel walking modes with plain driving when
// moving uphill on sand: wheel walking caused significantly less erosion", Field Experiment 6.6).
// On 8°, which both climb (the slope sweep's windowed steepest on unit 1: driving 12.5°, rolking
// 16.0°), on seeds 1–4 (2026-12-02) driving climbs 2.44–2.57 m and rolking 0.40–0.42 m; driving
// disturbs 2.6–2.8 times as much soil in all (0.021 against 0.0076–0.0081 m³: its six wheels slip
// through the sand the whole time, rolking's mostly stand) and less than half as much per metre
// climbed (0.008–0.009 against 0.018–0.020 m³/m). So wheel walking erodes less in all, as the
// thesis found, but not per metre, and on a slope both climb driving is the faster by far.
// (Before rolking's slope placement, 2026-12-02, rolking climbed 0.13–0.15 m here, disturbing
// 0.005 m³, 0.038 m³/m.) (Until soil laid back in a rut lay loose there,
// 2026-12-01, this ran on 12°, where rolking then climbed 0.02–0.10 m on the rut's raised level;
// now it slides back 0.2–1.5 cm there.)
Scenario soft_sand_climb(const std::string& name, const std::string& targets) {
  const ScratchFolder folder;
  return load_scenario(folder.write(name + ".toml", R"(
name = ")" + name + R"("
duration_s = 30.0
[terrain]
kind = "slope"
slope_deg = 8.0
material = "sand"
[sim]
supply = "battery"
[[input]]
t = 0.0
targets = { v1 = 0.0 }
[[input]]
t = 2.5
targets = )" + targets + R"(
[[phase]]
name = "climb"
from_s = 3.0
to_s = 30.0
)"));
}

TEST(ShippedScenarios, OnSoftSandDrivingClimbsFurtherThanRolkingAndErodesLessPerMetre) {
  for (const std::uint64_t seed : {1u, 2u}) {
    RunOptions options;
    options.plots = false;
    options.seed = seed;
    const ScenarioResult driving =
        run_scenario(soft_sand_climb("driving", "{ v1 = 1.0 }"), shipped_params(), options);
    const ScenarioResult rolking = run_scenario(
        soft_sand_climb("rolking", R"({ gait = "rolking", gait_speed = 1.0 })"),
        shipped_params(), options);
    ASSERT_GT(rolking.metrics.at("climb.forward_distance_m"), 0.0) << report(rolking);
    EXPECT_GT(rolking.metrics.at("gait_state_changes"), 2.0) << report(rolking);
    EXPECT_GT(driving.metrics.at("climb.forward_distance_m"),
              rolking.metrics.at("climb.forward_distance_m"))
        << "seed " << seed << "\n" << report(driving) << report(rolking);
    EXPECT_LT(disturbed_per_metre_climbed(driving), disturbed_per_metre_climbed(rolking))
        << "seed " << seed << "\n" << report(driving) << report(rolking);
    EXPECT_GT(driving.metrics.at("soil_disturbed_m3"), rolking.metrics.at("soil_disturbed_m3"))
        << "seed " << seed;
  }
}

}  // namespace
}  // namespace marsokhod::runner
