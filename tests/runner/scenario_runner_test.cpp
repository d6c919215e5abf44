// runner::run_scenario: metrics of the run and of its phases, checks (ratio_of too), and the
// determinism the recordings rely on.
#include "runner/scenario_runner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include "runner/metrics.hpp"
#include "runner/soil_metrics.hpp"
#include "runner_test_support.hpp"

namespace marsokhod::runner {
namespace {

using testing::ScratchFolder;
using testing::shipped_params;

// Start-up (about 2 s), then 2 s of driving forward at v1 = 1.5 rad/s.
constexpr const char* kShortDrive = R"(
duration_s = 4.0
seed = 3
[sim]
supply = "battery"
[[input]]
t = 0.0
targets = { v1 = 0.0 }
[[input]]
t = 2.5
targets = { v1 = 1.5 }
[[phase]]
name = "standing"
from_s = 0.5
to_s = 2.0
[[phase]]
name = "driving"
from_s = 3.0
to_s = 4.0
[[check]]
name = "mean speed from its parts"
ratio_of = ["driving.path_length_m", "driving.duration_s"]
min = 0.05
[[check]]
metric = "standing.distance_m"
max = 0.01
[[check]]
name = "needs a stop that never happens"
metric = "time_to_standstill_s"
max = 1.0
)";

ScenarioResult run(const std::string& text, std::optional<std::uint64_t> seed = std::nullopt,
                   std::optional<double> physics_step_s = std::nullopt) {
  const ScratchFolder folder;
  const Scenario scenario = load_scenario(folder.write("short.toml", text));
  RunOptions options;
  options.seed = seed;
  options.plots = false;
  options.physics_step_s = physics_step_s;
  return run_scenario(scenario, shipped_params(), options);
}

TEST(ScenarioRunner, APhysicsStepOfItsOwnReachesTheSimulator) {
  // The same drive at MuJoCo's 2 ms instead of the shipped 1 ms: another discretisation of the
  // same physics, so the numbers differ, but a second of straight driving on hard ground covers
  // the same distance within 2 %.
  const ScenarioResult shipped = run(kShortDrive);
  const ScenarioResult coarse = run(kShortDrive, std::nullopt, 0.002);
  const double d1 = shipped.metrics.at("driving.forward_distance_m");
  const double d2 = coarse.metrics.at("driving.forward_distance_m");
  EXPECT_NE(d1, d2);
  EXPECT_NEAR(d2, d1, 0.02 * d1);
  EXPECT_EQ(run(kShortDrive, std::nullopt, 0.001).metrics, shipped.metrics);
}

// On soft soil the grid's metrics are reported: finite, and after two seconds of driving every
// wheel stands in a rut and soil was compacted.
TEST(ScenarioRunner, OnSoftSoilReportsTheGridsMetrics) {
  std::string text = kShortDrive;
  text.replace(text.find("[sim]"), 5,
               "[terrain]\nkind = \"flat\"\nmaterial = \"sand\"\n[sim]");
  const ScenarioResult r = run(text);
  for (const std::string& name : soil_metric_names()) {
    ASSERT_TRUE(r.metrics.contains(name)) << name;
    EXPECT_TRUE(std::isfinite(r.metrics.at(name))) << name;
  }
  const auto& m = r.metrics;
  EXPECT_GT(m.at("soil_compacted_m3"), 0.0);
  EXPECT_GT(m.at("soil_disturbed_m3"), 0.0);
  EXPECT_GT(m.at("final_center_rut_depth_m"), 0.005);  // Bekker's static sinkage is 1–3 cm
  EXPECT_GT(m.at("final_exterior_rut_depth_m"), 0.005);
  // Driving, no wheel digs a trench of its own (m3's, where the exterior ruts go deeper): the
  // centre wheels, which carry the centre unit, sink deepest. Bekker's static sinkage goes as
  // the load to the power 2/(2n + 1) = 0.625; for a centre wheel's ≈ 220 N against an exterior
  // one's ≈ 90 N the exterior ruts are 0.57 as deep (measured: 1.46 against 2.54 cm, 0.58).
  EXPECT_LT(m.at("final_trench_depth_m"), 0.0);
  EXPECT_NEAR(m.at("final_exterior_rut_depth_m") / m.at("final_center_rut_depth_m"), 0.57, 0.1);
}

TEST(ScenarioRunner, ReportsTheRunsAndEachPhasesMetrics) {
  const ScenarioResult r = run(kShortDrive);
  EXPECT_EQ(r.seed, 3u);
  EXPECT_NEAR(r.sim_time_s, 4.0, 0.016);
  const std::vector<std::string>& soil = soil_metric_names();
  for (const std::string& name : run_metric_names()) {
    if (name == "time_to_standstill_s" || name == "time_to_motors_off_s") continue;  // no stop
    // Rigid ground has no soil grid: the soil's metrics are not reported.
    const bool soil_metric = std::find(soil.begin(), soil.end(), name) != soil.end();
    EXPECT_EQ(r.metrics.contains(name), !soil_metric) << name;
  }
  for (const char* phase : {"standing", "driving"}) {
    for (const std::string& name : phase_metric_names()) {
      EXPECT_TRUE(r.metrics.contains(std::string(phase) + "." + name)) << phase << "." << name;
    }
  }
  const std::vector<Phase> phases{{"standing", 0.5, 2.0}, {"driving", 3.0, 4.0}};
  for (const auto& [name, value] : r.metrics) {
    EXPECT_TRUE(is_metric_name(name, phases)) << name << " is not documented in metrics.hpp";
    EXPECT_TRUE(std::isfinite(value)) << name;
  }
  // A phase spans whole cycles from its start to its end (h = 15.6 ms).
  EXPECT_NEAR(r.metrics.at("driving.duration_s"), 1.0, 0.016);
  EXPECT_LT(r.metrics.at("standing.distance_m"), 0.01);
  EXPECT_GT(r.metrics.at("driving.forward_distance_m"), 0.05);
  EXPECT_LE(r.metrics.at("driving.forward_distance_m"), r.metrics.at("forward_distance_m"));
  EXPECT_GT(r.metrics.at("driving.energy_used_j"), 0.0);
  EXPECT_LT(r.metrics.at("driving.energy_used_j"), r.metrics.at("energy_used_j"));
  EXPECT_DOUBLE_EQ(r.metrics.at("driving.mean_speed_mps"),
                   r.metrics.at("driving.path_length_m") / r.metrics.at("driving.duration_s"));
  EXPECT_DOUBLE_EQ(r.metrics.at("driving.yaw_rate_mean_radps"),
                   r.metrics.at("driving.yaw_change_rad") / r.metrics.at("driving.duration_s"));
  // The joints' extremes bracket the angle they end at; no gait runs, no state changes.
  for (const char* joint : {"front", "rear"}) {
    const std::string j(joint);
    EXPECT_LE(r.metrics.at("driving.min_" + j + "_joint_rad"),
              r.metrics.at("driving.max_" + j + "_joint_rad"));
    EXPECT_NEAR(r.metrics.at("driving.final_" + j + "_joint_rad"),
                r.metrics.at("driving.max_" + j + "_joint_rad"), 0.01);
  }
  EXPECT_EQ(r.metrics.at("driving.gait_state_changes"), 0.0);
  // Joints held, the rover drives as one body: both exterior axles go as far as the centre.
  EXPECT_NEAR(r.metrics.at("driving.front_axle_forward_m"),
              r.metrics.at("driving.forward_distance_m"), 0.005);
  EXPECT_NEAR(r.metrics.at("driving.rear_axle_forward_m"),
              r.metrics.at("driving.forward_distance_m"), 0.005);
  // The mean forward position: standing, where the rover stands; driving (the run's last phase),
  // between where the phase began and where it ended.
  EXPECT_LT(std::abs(r.metrics.at("standing.mean_forward_m")), 0.01);
  const double end_m = r.metrics.at("forward_distance_m");
  const double start_m = end_m - r.metrics.at("driving.forward_distance_m");
  EXPECT_GT(r.metrics.at("driving.mean_forward_m"), start_m);
  EXPECT_LT(r.metrics.at("driving.mean_forward_m"), end_m);
  // The axle distances at the phase's end: the joints rest contracted after start-up (Remark
  // 3.1), γ = acos(a/b), where the lever stands vertical and c = sqrt(b² − a²) = 0.3867 m (Figure
  // 3.3); the law of cosines from the final angle must give the same c.
  const GeometryParams& g = shipped_params().geometry;
  const double a = g.joint_to_exterior_axle_m, b = g.center_axle_to_joint_m;
  const double gamma_front = -r.metrics.at("driving.final_front_joint_rad");
  const double gamma_rear = r.metrics.at("driving.final_rear_joint_rad");
  EXPECT_DOUBLE_EQ(r.metrics.at("driving.final_front_clearance_m"),
                   std::sqrt(a * a + b * b - 2.0 * a * b * std::cos(gamma_front)));
  EXPECT_DOUBLE_EQ(r.metrics.at("driving.final_rear_clearance_m"),
                   std::sqrt(a * a + b * b - 2.0 * a * b * std::cos(gamma_rear)));
  EXPECT_NEAR(r.metrics.at("driving.final_front_clearance_m"), std::sqrt(b * b - a * a), 0.005);
  EXPECT_NEAR(r.metrics.at("driving.final_rear_clearance_m"), 0.3867, 0.005);
}

TEST(ScenarioRunner, EvaluatesRatiosAndReportsAMissingMetric) {
  const ScenarioResult r = run(kShortDrive);
  ASSERT_EQ(r.checks.size(), 3u);
  EXPECT_EQ(r.checks[0].value,
            r.metrics.at("driving.path_length_m") / r.metrics.at("driving.duration_s"));
  EXPECT_TRUE(r.checks[0].passed);
  EXPECT_EQ(r.checks[0].limit, ">= 0.05");
  EXPECT_TRUE(r.checks[1].passed);
  // No operator silence and no halt in this run: the metric does not exist, the check fails.
  EXPECT_FALSE(r.checks[2].passed);
  EXPECT_NE(r.checks[2].limit.find("no such metric"), std::string::npos) << r.checks[2].limit;
  EXPECT_FALSE(r.passed);
  const auto json = to_json(r);
  EXPECT_TRUE(json["checks"][2]["value"].is_null());
}

TEST(ScenarioRunner, OneSeedGivesTheSameMetricsBitForBit) {
  const ScenarioResult a = run(kShortDrive);
  const ScenarioResult b = run(kShortDrive);
  ASSERT_EQ(a.metrics.size(), b.metrics.size());
  for (const auto& [name, value] : a.metrics) {
    ASSERT_TRUE(b.metrics.contains(name)) << name;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(value), std::bit_cast<std::uint64_t>(b.metrics.at(name)))
        << name << ": " << value << " vs " << b.metrics.at(name);
  }
}

TEST(ScenarioRunner, AnotherSeedGivesAnotherRover) {
  const ScenarioResult a = run(kShortDrive);
  const ScenarioResult b = run(kShortDrive, 4);
  EXPECT_EQ(b.seed, 4u);
  // The seed draws the rover's per-unit truth (ζ, droop, sensor tables, noise): the energy it
  // uses and the way it covers differ.
  EXPECT_NE(a.metrics.at("energy_used_j"), b.metrics.at("energy_used_j"));
  EXPECT_NE(a.metrics.at("path_length_m"), b.metrics.at("path_length_m"));
}

TEST(ScenarioRunner, StopsAreTimedFromTheOperatorsSilence) {
  const ScenarioResult r = run(R"(
duration_s = 5.0
[[input]]
t = 0.0
targets = { v1 = 0.0 }
[[input]]
t = 2.5
targets = { v1 = 1.0 }
[[input]]
t = 3.5
silent = true
)");
  // 0.5 s of operator timeout, then the ramp: the motors are off within the run.
  EXPECT_GT(r.metrics.at("time_to_motors_off_s"), 0.5);
  EXPECT_LT(r.metrics.at("time_to_motors_off_s"), 1.4);
  EXPECT_GE(r.metrics.at("time_to_standstill_s"), r.metrics.at("time_to_motors_off_s"));
  EXPECT_EQ(r.metrics.at("final_max_abs_duty"), 0.0);
  EXPECT_EQ(r.metrics.at("operator_timeouts"), 1.0);
}

}  // namespace
}  // namespace marsokhod::runner
