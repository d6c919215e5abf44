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
    checks::require_finite_estimate(vector[i], function, checks::Element{argument, i});
  }
}

}  // namespace

GravityEstimate::GravityEstimate(double gravity_mps2) {
  checks::require_positive(gravity_mps2, "GravityEstimate", "gravity_mps2");
  mean_mps2_ = {0.0, 0.0, -gravity_mps2};
}

void GravityEstimate::update(const Vector3& acceleration_mps2, double lambda) {
  constexpr const char* kFunction = "GravityEstimate::update";
  require_finite_vector(acceleration_mps2, kFunction, "acceleration_mps2");
  checks::require_within(lambda, 0.0, 1.0, kFunction, "lambda");
  if (lambda == 1.0) {
    throw std::invalid_argument(
        "GravityEstimate::update: lambda = 1 never learns from the accelerometer; use a value "
        "in [0, 1), close to 1 (FilterParams::gravity_lambda)");
  }
  if (norm(acceleration_mps2) == 0.0) {
    throw std::invalid_argument(
        "GravityEstimate::update: acceleration_mps2 = (0, 0, 0) has no direction; check the "
        "accelerometer (at rest it reads about 9.81 m/s²) and skip the update until it does");
  }
  Vector3 blended{};
  for (std::size_t i = 0; i < blended.size(); ++i) {
    blended[i] = lambda * mean_mps2_[i] + (1.0 - lambda) * acceleration_mps2[i];
  }
  mean_mps2_ = norm(blended) == 0.0 ? acceleration_mps2 : blended;
}

Vector3 GravityEstimate::direction() const {
  const double length = norm(mean_mps2_);
  return {mean_mps2_[0] / length, mean_mps2_[1] / length, mean_mps2_[2] / length};
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

SlopeEstimate::SlopeEstimate(double gravity_mps2) : gravity_(gravity_mps2) {}

void SlopeEstimate::update(const Vector3& acceleration_mps2, double front_lever_inclination_rad,
                           double rear_lever_inclination_rad, double lambda) {
  constexpr const char* kFunction = "SlopeEstimate::update";
  checks::require_finite_estimate(front_lever_inclination_rad, kFunction,
                                  "front_lever_inclination_rad");
  checks::require_finite_estimate(rear_lever_inclination_rad, kFunction,
                                  "rear_lever_inclination_rad");
  gravity_.update(acceleration_mps2, lambda);  // throws first: then nothing changed
  const double half_difference = (rear_lever_inclination_rad - front_lever_inclination_rad) / 2.0;
  correction_rad_ = lambda * correction_rad_ + (1.0 - lambda) * half_difference;
}

double SlopeEstimate::slope_rad() const {
  // The levers' part is the filtered correction, not the inclinations as they stand.
  return terrain_slope_rad(gravity_.direction(), 0.0, 0.0) + correction_rad_;
}

double slope_beyond_dead_band(double slope_rad, const BehaviourParams& params) {
  return std::abs(slope_rad) < params.slant_deadband_rad ? 0.0 : slope_rad;
}

double uphill_side(double slope_rad, const BehaviourParams& params) {
  const double slope = slope_beyond_dead_band(slope_rad, params);
  return slope > 0.0 ? 1.0 : (slope < 0.0 ? -1.0 : 0.0);
}

}  // namespace marsokhod::behaviour
