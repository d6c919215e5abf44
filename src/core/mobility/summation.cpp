#include "core/mobility/summation.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/checks/checks.hpp"

namespace marsokhod::mobility {
namespace {

checks::Element motor_argument(std::string_view vector, std::size_t motor) {
  return {vector, motor, kMotorNames[motor]};
}

void check_inputs(const MotorVector& driving, const MotorVector& walking,
                  const MotorVector& bounds) {
  constexpr std::string_view kWhere = "sum_motions";
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    checks::law::require_finite(driving[i], kWhere, motor_argument("driving_radps", i));
    checks::law::require_finite(walking[i], kWhere, motor_argument("walking_radps", i));
    checks::law::require_finite(bounds[i], kWhere, motor_argument("bounds_radps", i));
    if (bounds[i] < 0.0) {
      std::ostringstream message;
      message << kWhere << ": " << checks::argument_name(motor_argument("bounds_radps", i))
              << " must be ≥ 0, got "
              << bounds[i] << "; (5.5) bounds |ŵ_i| by ζ_i·W(D)·U/Ū";
      throw std::invalid_argument(message.str());
    }
  }
}

// The largest λ ∈ [0, 1] with |λ·walking_i| ≤ bound_i for every motor.
double walking_scale(const MotorVector& walking, const MotorVector& bounds) {
  double scale = 1.0;
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    if (std::abs(walking[i]) > bounds[i]) {
      scale = std::min(scale, bounds[i] / std::abs(walking[i]));
    }
  }
  return scale;
}

}  // namespace

MotorVector motor_velocity_bounds(const MotorVector& scale, double max_duty,
                                  const adaptation::MotorCurve& curve, double supply_v,
                                  double nominal_supply_v) {
  constexpr std::string_view kWhere = "motor_velocity_bounds";
  checks::law::require_finite(max_duty, kWhere, "max_duty (D)");
  if (!(max_duty > 0.0 && max_duty <= 1.0)) {
    std::ostringstream message;
    message << kWhere << ": max_duty (D) must lie in (0, 1], got " << max_duty;
    throw std::invalid_argument(message.str());
  }
  checks::law::require_finite(supply_v, kWhere, "supply_v (U)");
  checks::law::require_positive(nominal_supply_v, kWhere, "nominal_supply_v (Ū, 24 V)");
  const double common = curve.velocity_radps(max_duty) * std::max(supply_v, 0.0) / nominal_supply_v;
  MotorVector bounds{};
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    checks::law::require_finite(scale[i], kWhere, motor_argument("scale (ζ)", i));
    bounds[i] = std::max(scale[i], 0.0) * common;
  }
  return bounds;
}

double driving_scale_limit(double driving_radps, double walking_radps, double bound_radps) {
  constexpr std::string_view kWhere = "driving_scale_limit";
  checks::law::require_finite(driving_radps, kWhere, "driving_radps (a)");
  checks::law::require_finite(walking_radps, kWhere, "walking_radps (b)");
  checks::law::require_finite(bound_radps, kWhere, "bound_radps (c)");
  if (driving_radps == 0.0) {
    return std::numeric_limits<double>::infinity();
  }
  const bool same_sign = (driving_radps > 0.0) == (walking_radps > 0.0) && walking_radps != 0.0;
  const double room =
      same_sign ? bound_radps - std::abs(walking_radps) : bound_radps + std::abs(walking_radps);
  return std::max(room, 0.0) / std::abs(driving_radps);
}

Summation sum_motions(const MotorVector& driving_radps, const MotorVector& walking_radps,
                      const MotorVector& bounds_radps) {
  check_inputs(driving_radps, walking_radps, bounds_radps);
  Summation result;
  result.walking_scale = walking_scale(walking_radps, bounds_radps);
  result.walking_scaled = result.walking_scale < 1.0;
  MotorVector walking{};
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    walking[i] = result.walking_scale * walking_radps[i];
  }
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    // The feasible κ form an interval containing 0 (|b| ≤ c); if κ = 1 is in it, this motor
    // does not bind. Testing that directly keeps κ = 1 exact where the closed form could round
    // to 1 − 1e-16.
    if (std::abs(driving_radps[i] + walking[i]) > bounds_radps[i]) {
      result.driving_scale = std::min(
          result.driving_scale, driving_scale_limit(driving_radps[i], walking[i], bounds_radps[i]));
    }
  }
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    result.velocities_radps[i] = result.driving_scale * driving_radps[i] + walking[i];
  }
  return result;
}

}  // namespace marsokhod::mobility
