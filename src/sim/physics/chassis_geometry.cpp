#include "sim/physics/chassis_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace marsokhod::sim {

double axle_distance_m(const GeometryParams& geometry, double bend_rad) {
  const double a = geometry.joint_to_exterior_axle_m;
  const double b = geometry.center_axle_to_joint_m;
  return std::sqrt(a * a + b * b - 2.0 * a * b * std::cos(bend_rad));
}

double strut_elevation_rad(const GeometryParams& geometry, double bend_rad) {
  const double a = geometry.joint_to_exterior_axle_m;
  const double b = geometry.center_axle_to_joint_m;
  const double c = axle_distance_m(geometry, bend_rad);
  return std::acos(std::clamp((b * b + c * c - a * a) / (2.0 * b * c), -1.0, 1.0));
}

double vertical_bend_rad(const GeometryParams& geometry) {
  return std::acos(geometry.joint_to_exterior_axle_m / geometry.center_axle_to_joint_m);
}

double bend_for_axle_distance_rad(const GeometryParams& geometry, double axle_distance_m) {
  const double a = geometry.joint_to_exterior_axle_m;
  const double b = geometry.center_axle_to_joint_m;
  const double c = axle_distance_m;
  return std::acos(std::clamp((a * a + b * b - c * c) / (2.0 * a * b), -1.0, 1.0));
}

BendRange mechanical_bend_range(const GeometryParams& geometry) {
  return {bend_for_axle_distance_rad(geometry, kMinAxleDistanceM),
          bend_for_axle_distance_rad(geometry, kMaxAxleDistanceM)};
}

void validate_geometry(const GeometryParams& geometry) {
  const double a = geometry.joint_to_exterior_axle_m;
  const double b = geometry.center_axle_to_joint_m;
  if (!(a > 0.0 && b > a && std::isfinite(b))) {
    throw std::invalid_argument("geometry: the model needs 0 < a < b (a = " + std::to_string(a) +
                                " m, b = " + std::to_string(b) + " m)");
  }
  if (!(geometry.wheel_radius_m > 0.0 && std::isfinite(geometry.wheel_radius_m))) {
    throw std::invalid_argument("geometry: the wheel radius must be positive");
  }
  if (!(geometry.track_width_m > 0.2 && std::isfinite(geometry.track_width_m))) {
    throw std::invalid_argument(
        "geometry: the track width must exceed 0.2 m (the wheels are "
        "0.15 m wide)");
  }
}

}  // namespace marsokhod::sim
