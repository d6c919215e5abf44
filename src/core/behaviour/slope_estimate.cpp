#include "core/behaviour/slope_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>

#include "core/checks/checks.hpp"

namespace marsokhod::behaviour {
namespace {

double norm(const Vector3& vector) { return std::hypot(vector[0], vector[1], vector[2]); }

void require_finite_vector(const Vector3& vector, const char* function, const char* argument) {
  for (std::size_t i = 0; i < vector.size(); ++i) {
    checks::require_finite_estimate(vector[i], function, checks::argument_name(argument, i));
  }
}

}  // namespace

Vector3 next_gravity_direction(const Vector3& previous_direction, const Vector3& acceleration_mps2,
                               double lambda) {
  constexpr const char* kFunction = "next_gravity_direction";
  require_finite_vector(previous_direction, kFunction, "previous_direction");
  require_finite_vector(acceleration_mps2, kFunction, "acceleration_mps2");
  checks::require_within(lambda, 0.0, 1.0, kFunction, "lambda");
  if (lambda == 1.0) {
    throw std::invalid_argument(
        "next_gravity_direction: lambda = 1 never learns from the accelerometer; use a value "
        "in [0, 1), close to 1 (FilterParams::gravity_lambda)");
  }
  const double reading_norm_mps2 = norm(acceleration_mps2);
  if (reading_norm_mps2 == 0.0) {
    throw std::invalid_argument(
        "next_gravity_direction: acceleration_mps2 = (0, 0, 0) has no direction; check the "
        "accelerometer (at rest it reads about 9.81 m/s²) and skip the update until it does");
  }
  if (norm(previous_direction) == 0.0) {
    throw std::invalid_argument(
        "next_gravity_direction: previous_direction = (0, 0, 0); start from "
        "kInitialGravityDirection and pass the last returned direction");
  }
  Vector3 reading_direction{};
  Vector3 blended{};
  for (std::size_t i = 0; i < blended.size(); ++i) {
    reading_direction[i] = acceleration_mps2[i] / reading_norm_mps2;
    blended[i] = lambda * previous_direction[i] + (1.0 - lambda) * reading_direction[i];
  }
  const double blended_norm = norm(blended);
  if (blended_norm == 0.0) {
    return reading_direction;
  }
  for (double& component : blended) {
    component /= blended_norm;
  }
  return blended;
}

double terrain_slope_rad(const Vector3& gravity_direction, double front_lever_inclination_rad,
                         double rear_lever_inclination_rad) {
  constexpr const char* kFunction = "terrain_slope_rad";
  require_finite_vector(gravity_direction, kFunction, "gravity_direction");
  checks::require_finite_estimate(front_lever_inclination_rad, kFunction,
                                  "front_lever_inclination_rad");
  checks::require_finite_estimate(rear_lever_inclination_rad, kFunction,
                                  "rear_lever_inclination_rad");
  const double forward_component = std::clamp(gravity_direction[0], -1.0, 1.0);
  return std::acos(forward_component) - std::numbers::pi / 2.0 +
         (rear_lever_inclination_rad - front_lever_inclination_rad) / 2.0;
}

}  // namespace marsokhod::behaviour
