#include "runner/slope_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "runner/scenario_runner.hpp"

namespace marsokhod::runner {
namespace {

constexpr double kStartupS = 2.5;  // the driver's start-up takes about 2 s
constexpr double kPhaseStartS = 3.0;

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

}  // namespace

SteepestClimb find_steepest(const std::function<bool(double)>& climbs, double max_deg,
                            double step_deg) {
  if (!(step_deg > 0.0) || !(step_deg <= max_deg) || !std::isfinite(max_deg)) {
    std::ostringstream message;
    message << "find_steepest: need 0 < step (" << step_deg << "°) ≤ max (" << max_deg << "°)";
    throw std::invalid_argument(message.str());
  }
  SteepestClimb result;
  const auto ask = [&](long k) {
    const double angle = static_cast<double>(k) * step_deg;
    const bool climbed = climbs(angle);
    result.tried.emplace_back(angle, climbed);
    return climbed;
  };
  long low = 0;
  long high = static_cast<long>(std::floor(max_deg / step_deg + 1e-9));
  if (!ask(low)) return result;
  if (ask(high)) {
    result.steepest_deg = static_cast<double>(high) * step_deg;
    result.climbs_at_max = true;
    return result;
  }
  while (high - low > 1) {  // low climbs, high does not
    const long middle = low + (high - low) / 2;
    (ask(middle) ? low : high) = middle;
  }
  result.steepest_deg = static_cast<double>(low) * step_deg;
  return result;
}

double judged_advance_m(const std::map<std::string, double>& metrics, double window_s) {
  const double whole_m = metrics.at("climb.forward_distance_m");
  if (!(window_s > 0.0)) return whole_m;
  return std::min(whole_m, metrics.at("last.mean_forward_m") - metrics.at("before.mean_forward_m"));
}

Scenario slope_climb_scenario(mobility::Gait gait, double slope_deg, const ClimbSpec& spec) {
  Scenario s;
  std::ostringstream name;
  name << "slope-climb-" << (gait == mobility::Gait::kNone ? "driving" : mobility::gait_id(gait))
       << "-" << slope_deg;
  s.name = name.str();
  s.description = "a climb of the slope sweep (runner/slope_sweep.hpp)";
  s.duration_s = kPhaseStartS + spec.time_s;
  s.seed = spec.seed;
  s.sim.seed = spec.seed;
  s.sim.terrain.kind = sim::TerrainKind::kSlope;
  s.sim.terrain.slope_rad = radians(slope_deg);
  s.sim.terrain.ground = spec.ground;
  driver::OperatorInput still;
  still.targets.emplace();
  driver::OperatorInput climb;
  mobility::OperatorTargets& t = climb.targets.emplace();
  if (gait == mobility::Gait::kNone) {
    t.v1_radps = spec.drive_radps;
  } else {
    t.gait = gait;
    t.gait_speed = 1.0;
  }
  s.inputs = {{0.0, still}, {kStartupS, climb}};
  s.phases = {{"climb", kPhaseStartS, s.duration_s}};
  if (!(spec.window_s >= 0.0) || !std::isfinite(spec.window_s) ||
      2.0 * spec.window_s > spec.time_s) {
    std::ostringstream message;
    message << "slope climb: the window (" << spec.window_s
            << " s) must be at least 0 and at most half the climb (" << spec.time_s << " s)";
    throw std::invalid_argument(message.str());
  }
  if (spec.window_s > 0.0) {
    s.phases.push_back({"before", s.duration_s - 2.0 * spec.window_s, s.duration_s - spec.window_s});
    s.phases.push_back({"last", s.duration_s - spec.window_s, s.duration_s});
  }
  return s;
}

bool run_slope_climb(mobility::Gait gait, double slope_deg, const ClimbSpec& spec,
                     const Params& params, const Params* rover_params, double* advanced_m) {
  RunOptions options;
  options.plots = false;
  options.rover_params = rover_params;
  const ScenarioResult r = run_scenario(slope_climb_scenario(gait, slope_deg, spec), params, options);
  const double along = judged_advance_m(r.metrics, spec.window_s) / std::cos(radians(slope_deg));
  if (advanced_m != nullptr) *advanced_m = along;
  return along >= spec.distance_m;
}

}  // namespace marsokhod::runner
