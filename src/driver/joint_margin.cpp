#include "driver/joint_margin.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/adaptation/backlash.hpp"
#include "core/adaptation/no_load_estimator.hpp"
#include "core/tracking/clock.hpp"
#include <string>

namespace marsokhod::driver {

double joint_dead_time_s(const Params& params) {
  const ResponseParams& r =
      adaptation::select_response(params.responses, params.cycle.period_s, params.cycle.con);
  double weighted = 0.0;
  double total = 0.0;
  for (std::size_t j = 0; j < r.delta.size(); ++j) {
    weighted += static_cast<double>(j) * r.delta[j];
    total += r.delta[j];
  }
  const double h = params.cycle.period_s;
  const double mean_delay_s = total > 0.0 ? h * weighted / total : 0.0;
  return std::max(0.0, h + mean_delay_s - 0.5 * tracking::clock_overflow_period_s(params.cycle.con));
}

JointParams joint_bounds_with_backlash_margin(const JointParams& joints, const MotorParams& motors) {
  JointParams j = joints;
  j.front_max_rad -= joints.backlash_uncertainty * motors.backlash_rad[kFrontJoint];
  j.rear_max_rad -= joints.backlash_uncertainty * motors.backlash_rad[kRearJoint];
  if (!(j.front_max_rad > j.front_min_rad) || !(j.rear_max_rad > j.rear_min_rad)) {
    throw std::invalid_argument(
        "joint_bounds_with_backlash_margin: joints.backlash_uncertainty " +
        std::to_string(joints.backlash_uncertainty) + " leaves a joint no range within (5.3)");
  }
  return j;
}

double positive_bound_margin_rad(double backlash_uncertainty, double backlash_rad,
                                 double shaft_position_rad, double joint_position_rad) {
  if (backlash_rad <= 0.0) return 0.0;
  return backlash_uncertainty * backlash_rad *
         adaptation::backlash_factor_positive(shaft_position_rad, joint_position_rad, backlash_rad);
}

}  // namespace marsokhod::driver

namespace marsokhod::driver {

double run_on_limited_radps(double command_radps, double position_rad, double min_rad,
                            double max_rad, double run_on_s, double load_radps) {
  if (!(run_on_s >= 0.0) || !std::isfinite(load_radps)) {
    throw std::invalid_argument("run_on_limited_radps: run_on_s must be ≥ 0 and the load finite, got " +
                                std::to_string(run_on_s) + " s and " + std::to_string(load_radps) +
                                " rad/s");
  }
  if (run_on_s == 0.0) return command_radps;
  if (command_radps > 0.0) {
    const double limit = std::max(0.0, max_rad - position_rad) / run_on_s - load_radps;
    return std::min(command_radps, std::max(0.0, limit));
  }
  if (command_radps < 0.0) {
    const double limit = std::max(0.0, position_rad - min_rad) / run_on_s + load_radps;
    return std::max(command_radps, -std::max(0.0, limit));
  }
  return command_radps;
}

}  // namespace marsokhod::driver
