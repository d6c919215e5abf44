// The steepest slope the simulated rover climbs, by driving and by each gait (issue #14, [KG92]:
// 20° by driving, 25–30° by wheel walking, never beyond the angle of repose).
//
// A climb: the rover starts square to a slope of the ground's material, joints vertical; after the
// start-up (2.5 s) the operator drives straight at v1 = drive_radps, or runs the gait at full
// speed (s = 1), for time_s. It climbed when in that time it advanced at least distance_m along
// the slope (forward_distance_m / cos θ, ground truth). With a window W > 0 it is judged at the
// end as well: it climbed when it also still gains distance_m there, its mean position along
// the slope over the last W seconds that far ahead of its mean over the W seconds before (the
// phases' mean_forward_m: a gait's strokes, back and forth, are averaged out); the advance
// reported is the smaller of the two. Over minutes a
// rover driving up soft sand digs itself in after its first metres (docs/simulator.md); the
// window sees whether a climb goes on. find_steepest bisects the angles 0,
// step, 2·step, … up to the angle of repose of the ground's soil, assuming a climb that
// succeeds on a slope succeeds on every gentler one.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/mobility/gait_table.hpp"
#include "core/params.hpp"
#include "runner/scenario.hpp"
#include "sim/physics/terrain.hpp"

namespace marsokhod::runner {

struct SteepestClimb {
  std::optional<double> steepest_deg;  // none: not even 0° was climbed
  bool climbs_at_max = false;          // it climbed the steepest angle tried (max_deg)
  std::vector<std::pair<double, bool>> tried;  // angle, climbed — in the order asked
};

// Bisection over the grid k·step_deg, k = 0 … ⌊max_deg/step_deg⌋ (at most ⌈log2 n⌉ + 2 calls).
// Throws std::invalid_argument unless 0 < step_deg ≤ max_deg.
SteepestClimb find_steepest(const std::function<bool(double)>& climbs, double max_deg,
                            double step_deg);

struct ClimbSpec {
  sim::Material ground;
  double drive_radps = 1.0;   // v1 when driving
  double time_s = 40.0;       // of driving or walking, after the start-up
  double distance_m = 0.1;    // along the slope
  std::uint64_t seed = 1;     // the rover unit
  double window_s = 0.0;      // W: 0 judges the whole climb; > 0 its end (above), 2W ≤ time_s
};

// The forward advance [m, along x] a climb's metrics are judged by: the whole climb's; with a
// window the smaller of it and what the end gained. The whole climb counts too because a rover
// that slid back for minutes can lurch forward at the end (unit 2 "climbed" 27.5° so, sliding
// back 2.7 m), and that is no climb.
double judged_advance_m(const std::map<std::string, double>& metrics, double window_s);

// The climb above as a scenario (gait kNone: driving). Throws std::invalid_argument for a window
// that is negative, not finite or longer than half the climb.
Scenario slope_climb_scenario(mobility::Gait gait, double slope_deg, const ClimbSpec& spec);

// Runs it; true when the rover climbed. `advanced_m` (optional) gets the advance along the slope
// (with a window, the smaller of the whole climb's and the end's).
bool run_slope_climb(mobility::Gait gait, double slope_deg, const ClimbSpec& spec,
                     const Params& params, const Params* rover_params,
                     double* advanced_m = nullptr);

}  // namespace marsokhod::runner
