// The slope sweep (runner/slope_sweep.hpp): the bisection on a known answer, and a small sweep of
// simulated climbs whose answer a direct climb on each side of it confirms.
#include "runner/slope_sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

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

}  // namespace
}  // namespace marsokhod::runner
