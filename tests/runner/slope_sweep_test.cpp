// The slope sweep (runner/slope_sweep.hpp): the bisection on a known answer, and a small sweep of
// simulated climbs whose answer a direct climb on each side of it confirms.
#include "runner/slope_sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "runner/scenario_runner.hpp"
#include "runner_test_support.hpp"

namespace marsokhod::runner {
namespace {

// A rover that climbs up to 13.2°: on the 0.5° grid up to 28° the steepest is 13.0°, found in at
// most ⌈log2 56⌉ + 2 = 8 climbs, the last failure 13.5°.
TEST(SlopeSweep, BisectionFindsTheLastGridAngleClimbed) {
  int calls = 0;
  const SteepestClimb found = find_steepest(
      [&](double deg) {
        ++calls;
        return deg <= 13.2;
      },
      28.0, 0.5);
  ASSERT_TRUE(found.steepest_deg);
  EXPECT_EQ(*found.steepest_deg, 13.0);
  EXPECT_FALSE(found.climbs_at_max);
  EXPECT_LE(calls, 8);
  EXPECT_EQ(found.tried.size(), static_cast<std::size_t>(calls));
  bool saw_failure_above = false;
  for (const auto& [deg, climbed] : found.tried) {
    EXPECT_EQ(climbed, deg <= 13.2) << deg;
    saw_failure_above = saw_failure_above || deg == 13.5;
  }
  EXPECT_TRUE(saw_failure_above);
  // Everything climbed: the steepest is the grid's top (28°); nothing: none.
  const SteepestClimb all = find_steepest([](double) { return true; }, 28.0, 0.5);
  EXPECT_EQ(all.steepest_deg, 28.0);
  EXPECT_TRUE(all.climbs_at_max);
  const SteepestClimb none = find_steepest([](double) { return false; }, 28.0, 0.5);
  EXPECT_FALSE(none.steepest_deg);
  EXPECT_THROW(find_steepest([](double) { return true; }, 28.0, 0.0), std::invalid_argument);
  EXPECT_THROW(find_steepest([](double) { return true; }, 0.2, 0.5), std::invalid_argument);
}

// A small sweep: driving at 1 rad/s on soft sand, 8 s to advance 5 cm along the slope, 5° steps
// up to 20°. On flat soft sand it advances (RoverSoftSoil.DrivesForwardWithSlip). Whatever the
// steepest angle found, a climb there succeeds and one a step steeper fails — the bisection's
// answer confirmed by direct runs — and two sweeps give the same answer (deterministic).
TEST(SlopeSweep, ASmallSweepOfDrivingOnSoftSandIsConfirmedByDirectClimbs) {
  const Params params = testing::shipped_params();
  ClimbSpec spec;
  spec.ground = sim::sand();
  spec.time_s = 8.0;
  spec.distance_m = 0.05;
  const auto climbs = [&](double deg) {
    return run_slope_climb(mobility::Gait::kNone, deg, spec, params, nullptr);
  };
  const SteepestClimb found = find_steepest(climbs, 20.0, 5.0);
  ASSERT_TRUE(found.steepest_deg) << "not even flat soft sand was climbed";
  double advanced = 0.0;
  EXPECT_TRUE(run_slope_climb(mobility::Gait::kNone, *found.steepest_deg, spec, params, nullptr,
                              &advanced));
  EXPECT_GE(advanced, spec.distance_m);
  if (!found.climbs_at_max) {
    EXPECT_FALSE(run_slope_climb(mobility::Gait::kNone, *found.steepest_deg + 5.0, spec, params,
                                 nullptr, &advanced));
    EXPECT_LT(advanced, spec.distance_m);
  }
  EXPECT_EQ(find_steepest(climbs, 20.0, 5.0).steepest_deg, found.steepest_deg);
}

// The window judges a climb by its end: on flat hard ground at v1 = 1 rad/s the wheels roll at
// r·v1 = 0.125 m/s without slip, so the mean positions of two 4-s windows lie 0.5 m apart.
TEST(SlopeSweep, AWindowMeasuresTheAdvanceBetweenTheLastTwoWindowsMeans) {
  ClimbSpec spec;
  spec.ground = sim::hard_ground();
  spec.time_s = 12.0;
  spec.window_s = 4.0;
  const Scenario scenario = slope_climb_scenario(mobility::Gait::kNone, 0.0, spec);
  ASSERT_EQ(scenario.phases.size(), 3u);
  EXPECT_DOUBLE_EQ(scenario.phases[1].from_s, scenario.duration_s - 8.0);
  EXPECT_DOUBLE_EQ(scenario.phases[1].to_s, scenario.duration_s - 4.0);
  EXPECT_DOUBLE_EQ(scenario.phases[2].to_s, scenario.duration_s);
  double advanced = 0.0;
  EXPECT_TRUE(run_slope_climb(mobility::Gait::kNone, 0.0, spec, testing::shipped_params(),
                              nullptr, &advanced));
  EXPECT_NEAR(advanced, 0.125 * 4.0, 0.025);
  for (const double bad : {-1.0, 6.5, std::nan("")}) {
    spec.window_s = bad;
    EXPECT_THROW(slope_climb_scenario(mobility::Gait::kNone, 0.0, spec), std::invalid_argument)
        << bad;
  }
}

// With a window a climb is judged by the smaller of the whole climb's advance and the end's: a
// rover that slid back 0.5 m and lurches 5 cm forward at the end did not climb.
TEST(SlopeSweep, AWindowedClimbMustAlsoHaveGainedOverTheWhole) {
  const std::map<std::string, double> slid{{"climb.forward_distance_m", -0.5},
                                           {"before.mean_forward_m", -0.55},
                                           {"last.mean_forward_m", -0.50}};
  EXPECT_DOUBLE_EQ(judged_advance_m(slid, 20.0), -0.5);
  EXPECT_DOUBLE_EQ(judged_advance_m(slid, 0.0), -0.5);
  const std::map<std::string, double> dug_in{{"climb.forward_distance_m", 1.2},
                                             {"before.mean_forward_m", 1.18},
                                             {"last.mean_forward_m", 1.19}};
  EXPECT_NEAR(judged_advance_m(dug_in, 20.0), 0.01, 1e-12);
  EXPECT_DOUBLE_EQ(judged_advance_m(dug_in, 0.0), 1.2);
}

// Driving can hold a climb only while its wheels' drawbar pull outweighs the slope: on the soil
// model's sand a Marsokhod wheel's steady pull peaks at 0.238 of its load (slip 0.8, the Wong–Reece
// table in docs/simulator.md), so six driven wheels climb at most atan 0.238 = 13.4° for good.
// On 10° (tan 10° = 0.176) the rover still advances by the window at the end of a 120-s climb; on
// 16° it gains only the first decimetre, while its wheels dig in, and by the end has stopped (one
// run read both ways: the whole climb and the window). Until soil laid back in a rut lay loose
// there (2026-12-01) the rut's raised undisturbed level propped the wheels and driving gained
// 0.76 m on 16° before it stopped.
double advance_by_the_window_m(double slope_deg, double* whole_m) {
  ClimbSpec spec;
  spec.ground = sim::sand();
  spec.time_s = 120.0;
  spec.window_s = 20.0;
  RunOptions options;
  options.plots = false;
  const ScenarioResult r = run_scenario(
      slope_climb_scenario(mobility::Gait::kNone, slope_deg, spec), testing::shipped_params(),
      options);
  const double along = 1.0 / std::cos(slope_deg * std::numbers::pi / 180.0);
  *whole_m = r.metrics.at("climb.forward_distance_m") * along;
  return (r.metrics.at("last.mean_forward_m") - r.metrics.at("before.mean_forward_m")) * along;
}

TEST(SlopeSweep, DrivingKeepsClimbingBelowTheDrawbarPullsLimitAndStopsAboveIt) {
  double whole_m = 0.0;
  EXPECT_GT(advance_by_the_window_m(10.0, &whole_m), 0.05);
  EXPECT_GT(whole_m, 0.5);
  EXPECT_LT(advance_by_the_window_m(16.0, &whole_m), 0.02);
  EXPECT_LT(whole_m, 0.5);
}

}  // namespace
}  // namespace marsokhod::runner
