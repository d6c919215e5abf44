#include "driver/joint_margin.hpp"

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
