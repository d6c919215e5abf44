#include "core/mobility/joint_compensation.hpp"

#include <string_view>

#include "core/checks/checks.hpp"
#include "core/mobility/elementary_motion.hpp"
#include "core/mobility/lever_geometry.hpp"

namespace marsokhod::mobility {
namespace {

// The three columns of one row of (5.1)/(5.2), seen from the bending joint: `own` is the
// joint's exterior axle (front for n6, rear for n7), `far` the other exterior axle.
struct CompensationColumns {
  double far = 0.0;
  double center = 0.0;
  double own = 0.0;
};

CompensationColumns compensation_columns(double bending_rad, double axle_factor,
                                         const GeometryParams& geometry) {
  const LeverRates rates = lever_rates(bending_rad, geometry);
  const double u = rates.clearance_m_per_rad / geometry.wheel_radius_m;
  return {(1.0 - axle_factor) * u, (1.0 - axle_factor) * u + 0.5 * rates.joint_angle_rate,
          -axle_factor * u - rates.exterior_angle_rate};
}

}  // namespace

double clearance_wheel_rate(double bending_rad, const GeometryParams& geometry) {
  return lever_rates(bending_rad, geometry).clearance_m_per_rad / geometry.wheel_radius_m;
}

MotorVector front_joint_compensation(double front_joint_position_rad, double front_axle_factor,
                                     const GeometryParams& geometry) {
  checks::law::require_finite(front_axle_factor, "front_joint_compensation",
                              "front_axle_factor (ρf)");
  const CompensationColumns columns = compensation_columns(
      front_joint_bending_rad(front_joint_position_rad), front_axle_factor, geometry);
  MotorVector n6{};
  n6[kBackLeft] = n6[kBackRight] = columns.far;
  n6[kCenterLeft] = n6[kCenterRight] = columns.center;
  n6[kFrontLeft] = n6[kFrontRight] = columns.own;
  return n6;
}

MotorVector rear_joint_compensation(double rear_joint_position_rad, double rear_axle_factor,
                                    const GeometryParams& geometry) {
  checks::law::require_finite(rear_axle_factor, "rear_joint_compensation", "rear_axle_factor (ρr)");
  const CompensationColumns columns = compensation_columns(
      rear_joint_bending_rad(rear_joint_position_rad), rear_axle_factor, geometry);
  MotorVector n7{};
  n7[kBackLeft] = n7[kBackRight] = columns.own;
  n7[kCenterLeft] = n7[kCenterRight] = columns.center;
  n7[kFrontLeft] = n7[kFrontRight] = columns.far;
  return n7;
}

MotorVector walking_motion(const WalkingInput& input, const GeometryParams& geometry) {
  constexpr std::string_view kWhere = "walking_motion";
  checks::law::require_finite(input.front_joint_command_radps, kWhere,
                          "front_joint_command_radps (v6)");
  checks::law::require_finite(input.rear_joint_command_radps, kWhere,
                              "rear_joint_command_radps (v7)");
  checks::law::require_finite(input.front_joint_velocity_radps, kWhere,
                          "front_joint_velocity_radps (w6)");
  checks::law::require_finite(input.rear_joint_velocity_radps, kWhere,
                          "rear_joint_velocity_radps (w7)");
  MotorVector motion{};
  add_scaled(motion, front_joint_motion(), input.front_joint_command_radps);
  add_scaled(
      motion,
      front_joint_compensation(input.front_joint_position_rad, input.front_axle_factor, geometry),
      input.front_joint_velocity_radps);
  add_scaled(motion, rear_joint_motion(), input.rear_joint_command_radps);
  add_scaled(
      motion,
      rear_joint_compensation(input.rear_joint_position_rad, input.rear_axle_factor, geometry),
      input.rear_joint_velocity_radps);
  return motion;
}

}  // namespace marsokhod::mobility
