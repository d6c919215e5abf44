#include "core/mobility/lever_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/checks/checks.hpp"

namespace marsokhod::mobility {
namespace {

[[noreturn]] void reject(std::string_view where, std::string_view problem) {
  std::ostringstream message;
  message << where << ": " << problem << "; fix it in config/marsokhod.toml";
  throw std::invalid_argument(message.str());
}

void require_interval(double min_rad, double max_rad, std::string_view name) {
  if (!std::isfinite(min_rad) || !std::isfinite(max_rad) || !(min_rad < max_rad)) {
    std::ostringstream problem;
    problem << name << " must be a finite interval with min < max, got [" << min_rad << ", "
            << max_rad << "]";
    reject("JointParams", problem.str());
  }
}

}  // namespace

void validate(const GeometryParams& geometry) {
  constexpr std::string_view kWhere = "GeometryParams";
  checks::law::require_positive(geometry.joint_to_exterior_axle_m, kWhere,
                            "joint_to_exterior_axle_m (a, 0.145 m)");
  checks::law::require_positive(geometry.center_axle_to_joint_m, kWhere,
                            "center_axle_to_joint_m (b, 0.413 m)");
  checks::law::require_positive(geometry.wheel_radius_m, kWhere,
                                "wheel_radius_m (r, 0.115..0.125 m)");
  if (!(geometry.joint_to_exterior_axle_m < geometry.center_axle_to_joint_m)) {
    reject(kWhere,
           "joint_to_exterior_axle_m (a) must be shorter than center_axle_to_joint_m (b), "
           "else acos(a/b) of (5.3) does not exist");
  }
}

void validate(const JointParams& joints) {
  require_interval(joints.front_min_rad, joints.front_max_rad, "front joint bounds (p6 of (5.3))");
  require_interval(joints.rear_min_rad, joints.rear_max_rad, "rear joint bounds (p7 of (5.3))");
  checks::law::require_positive(joints.control_rate_per_s, "JointParams",
                            "control_rate_per_s (μ of (4.15), 0.4)");
  checks::law::require_positive(joints.target_tolerance_rad, "JointParams",
                            "target_tolerance_rad (0.05, Procedure 4.17)");
}

double front_joint_bending_rad(double front_joint_position_rad) {
  checks::law::require_finite(front_joint_position_rad, "front_joint_bending_rad", "p6");
  return -front_joint_position_rad;
}

double rear_joint_bending_rad(double rear_joint_position_rad) {
  checks::law::require_finite(rear_joint_position_rad, "rear_joint_bending_rad", "p7");
  return rear_joint_position_rad;
}

double contracted_bending_rad(const GeometryParams& geometry) {
  validate(geometry);
  return std::acos(geometry.joint_to_exterior_axle_m / geometry.center_axle_to_joint_m);
}

double axle_clearance_m(double bending_rad, const GeometryParams& geometry) {
  checks::law::require_finite(bending_rad, "axle_clearance_m", "bending_rad (γ)");
  validate(geometry);
  const double a = geometry.joint_to_exterior_axle_m;
  const double b = geometry.center_axle_to_joint_m;
  // a < b keeps c ≥ b − a > 0 for every γ.
  return std::sqrt(a * a + b * b - 2.0 * a * b * std::cos(bending_rad));
}

double lever_inclination_rad(double bending_rad, const GeometryParams& geometry) {
  const double c = axle_clearance_m(bending_rad, geometry);
  const double a = geometry.joint_to_exterior_axle_m;
  const double b = geometry.center_axle_to_joint_m;
  return std::acos(std::clamp((b * b + c * c - a * a) / (2.0 * b * c), -1.0, 1.0));
}

LeverRates lever_rates(double bending_rad, const GeometryParams& geometry) {
  const double c = axle_clearance_m(bending_rad, geometry);
  const double a = geometry.joint_to_exterior_axle_m;
  const double b = geometry.center_axle_to_joint_m;
  const double cos_gamma = std::cos(bending_rad);
  return {a * b * std::sin(bending_rad) / c, b * (b - a * cos_gamma) / (c * c),
          a * (a - b * cos_gamma) / (c * c)};
}

Lever front_lever(double front_joint_position_rad, const GeometryParams& geometry) {
  const double gamma = front_joint_bending_rad(front_joint_position_rad);
  return {gamma, axle_clearance_m(gamma, geometry), lever_inclination_rad(gamma, geometry)};
}

Lever rear_lever(double rear_joint_position_rad, const GeometryParams& geometry) {
  const double gamma = rear_joint_bending_rad(rear_joint_position_rad);
  return {gamma, axle_clearance_m(gamma, geometry), lever_inclination_rad(gamma, geometry)};
}

double center_unit_pitch_rad(double front_joint_position_rad, double rear_joint_position_rad,
                             const GeometryParams& geometry) {
  return 0.5 * (front_lever(front_joint_position_rad, geometry).inclination_rad -
                rear_lever(rear_joint_position_rad, geometry).inclination_rad);
}

double JointBounds::clamp(double position_rad) const {
  checks::law::require_finite(position_rad, "JointBounds::clamp", "position_rad");
  return std::clamp(position_rad, min_rad, max_rad);
}

JointBounds front_joint_bounds(const JointParams& joints) {
  validate(joints);
  return {joints.front_min_rad, joints.front_max_rad};
}

JointBounds rear_joint_bounds(const JointParams& joints) {
  validate(joints);
  return {joints.rear_min_rad, joints.rear_max_rad};
}

}  // namespace marsokhod::mobility
