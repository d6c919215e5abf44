#include "core/behaviour/slant_response.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/checks/checks.hpp"

namespace marsokhod::behaviour {
namespace {

void require_interval(double lowest, double highest, const char* function, const char* lowest_name,
                      const char* highest_name) {
  checks::require_finite_estimate(lowest, function, lowest_name);
  checks::require_finite_estimate(highest, function, highest_name);
  if (lowest > highest) {
    throw std::invalid_argument(std::string(function) + ": " + lowest_name + " exceeds " +
                                highest_name + "; the bounds (5.3) must satisfy min ≤ max");
  }
}

}  // namespace

JointBounds joint_bounds_of(const JointParams& joints) {
  constexpr const char* kFunction = "joint_bounds_of";
  require_interval(joints.front_min_rad, joints.front_max_rad, kFunction, "joints.front_min_rad",
                   "joints.front_max_rad");
  require_interval(joints.rear_min_rad, joints.rear_max_rad, kFunction, "joints.rear_min_rad",
                   "joints.rear_max_rad");
  return JointBounds{joints.front_min_rad, joints.front_max_rad, joints.rear_min_rad,
                     joints.rear_max_rad};
}

double gravity_parallel_joint_angle_rad(double slope_rad, const GeometryParams& geometry) {
  constexpr const char* kFunction = "gravity_parallel_joint_angle_rad";
  checks::require_finite_estimate(slope_rad, kFunction, "slope_rad");
  const double a = geometry.joint_to_exterior_axle_m;
  const double b = geometry.center_axle_to_joint_m;
  checks::require_positive(a, kFunction, "geometry.joint_to_exterior_axle_m");
  checks::require_positive(b, kFunction, "geometry.center_axle_to_joint_m");
  if (!(a < b)) {
    throw std::invalid_argument(
        "gravity_parallel_joint_angle_rad: geometry.joint_to_exterior_axle_m (a) must be "
        "shorter than geometry.center_axle_to_joint_m (b), as on the rover (0.145 m < 0.413 m)");
  }
  const double sine_squared = std::sin(slope_rad) * std::sin(slope_rad);
  const double s = -1.0 + sine_squared;
  // a² s + b² ≥ b² − a² > 0, so the root is real for every σ.
  const double cosine = -(a * s + std::sqrt((a * a * s + b * b) * sine_squared)) / b;
  return std::acos(std::clamp(cosine, -1.0, 1.0));
}

JointBounds slant_joint_bounds(double slope_rad, const JointParams& joints,
                               const GeometryParams& geometry, const BehaviourSwitches& switches) {
  JointBounds bounds = joint_bounds_of(joints);
  const double joint_angle_rad = gravity_parallel_joint_angle_rad(slope_rad, geometry);
  if (!switches.slant_response) {
    return bounds;
  }
  if (slope_rad >= 0.0) {
    bounds.rear_min_rad = std::clamp(joint_angle_rad, joints.rear_min_rad, joints.rear_max_rad);
  } else {
    bounds.front_max_rad = std::clamp(-joint_angle_rad, joints.front_min_rad, joints.front_max_rad);
  }
  return bounds;
}

}  // namespace marsokhod::behaviour
