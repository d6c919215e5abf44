#include "driver/joint_margin.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/adaptation/backlash.hpp"
#include <string>

namespace marsokhod::driver {

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
