#include "core/mobility/axle_placement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "core/checks/checks.hpp"
#include "core/mobility/lever_geometry.hpp"

namespace marsokhod::mobility {

DrivingIntent driving_intent(DrivingIntent previous, double drive_target_radps) {
  checks::law::require_finite(drive_target_radps, "driving_intent", "drive_target_radps (v1ᵈ)");
  if (drive_target_radps > 0.0) {
    return DrivingIntent::kForward;
  }
  if (drive_target_radps < 0.0) {
    return DrivingIntent::kBackward;
  }
  return previous;
}

double intent_value(DrivingIntent intent) { return intent == DrivingIntent::kBackward ? 1.0 : 0.0; }

double front_axle_factor(DrivingIntent intent, ClearanceIntent front_clearance) {
  const double varrho = intent_value(intent);
  return front_clearance == ClearanceIntent::kIncrease ? 1.0 - varrho : varrho;
}

double rear_axle_factor(DrivingIntent intent, ClearanceIntent rear_clearance) {
  const double varrho = intent_value(intent);
  return rear_clearance == ClearanceIntent::kIncrease ? varrho : 1.0 - varrho;
}

ClearanceIntent front_clearance_intent(double front_joint_velocity_radps) {
  checks::law::require_finite(front_joint_velocity_radps, "front_clearance_intent",
                          "front_joint_velocity_radps (w6)");
  return front_joint_velocity_radps < 0.0 ? ClearanceIntent::kIncrease : ClearanceIntent::kDecrease;
}

ClearanceIntent rear_clearance_intent(double rear_joint_velocity_radps) {
  checks::law::require_finite(rear_joint_velocity_radps, "rear_clearance_intent",
                          "rear_joint_velocity_radps (w7)");
  return rear_joint_velocity_radps > 0.0 ? ClearanceIntent::kIncrease : ClearanceIntent::kDecrease;
}

AxleDistanceRates axle_distance_rates(double front_joint_position_rad,
                                      double rear_joint_position_rad,
                                      double front_joint_velocity_radps,
                                      double rear_joint_velocity_radps,
                                      const GeometryParams& geometry) {
  checks::law::require_finite(front_joint_velocity_radps, "axle_distance_rates",
                          "front_joint_velocity_radps (w6)");
  checks::law::require_finite(rear_joint_velocity_radps, "axle_distance_rates",
                          "rear_joint_velocity_radps (w7)");
  const double front_rate =
      lever_rates(front_joint_bending_rad(front_joint_position_rad), geometry).clearance_m_per_rad;
  const double rear_rate =
      lever_rates(rear_joint_bending_rad(rear_joint_position_rad), geometry).clearance_m_per_rad;
  return {front_rate * front_joint_velocity_radps, rear_rate * rear_joint_velocity_radps};
}

AxleFactors two_joint_axle_factors(const AxleDistanceRates& rates, double epsilon) {
  constexpr std::string_view kWhere = "two_joint_axle_factors";
  checks::law::require_finite(rates.front_mps, kWhere, "rates.front_mps (yf)");
  checks::law::require_finite(rates.rear_mps, kWhere, "rates.rear_mps (yr)");
  checks::law::require_finite(epsilon, kWhere, "epsilon (ε)");
  if (epsilon < 0.0 || epsilon > 1.0) {
    std::ostringstream message;
    message << kWhere << ": epsilon (ε, the desired ρf) must lie in [0, 1], got " << epsilon;
    throw std::invalid_argument(message.str());
  }
  // The formula is homogeneous of degree 0 in (yf, yr): normalising by the larger rate avoids
  // underflow of yf² + yr² for tiny rates without changing the result.
  const double scale = std::max(std::abs(rates.front_mps), std::abs(rates.rear_mps));
  if (scale == 0.0) {
    return {epsilon, 1.0 - epsilon};
  }
  const double f = rates.front_mps / scale;
  const double r = rates.rear_mps / scale;
  const double denominator = 2.0 * (f * f + r * r);
  return {(f * f + (2.0 * epsilon - 1.0) * f * r + 2.0 * epsilon * r * r) / denominator,
          (2.0 * (1.0 - epsilon) * f * f + (1.0 - 2.0 * epsilon) * f * r + r * r) / denominator};
}

AxleFactors uphill_axle_factors(const AxleDistanceRates& rates, double epsilon, double uphill) {
  constexpr std::string_view kWhere = "uphill_axle_factors";
  // Validates the rates and ε (and is the answer for still joints).
  const AxleFactors even = two_joint_axle_factors(rates, epsilon);
  if (uphill != 1.0 && uphill != -1.0) {
    std::ostringstream message;
    message << kWhere << ": uphill (u) must be +1 or -1, got " << uphill;
    throw std::invalid_argument(message.str());
  }
  const double scale = std::max(std::abs(rates.front_mps), std::abs(rates.rear_mps));
  if (scale == 0.0) return even;
  const double f = rates.front_mps / scale;
  const double r = rates.rear_mps / scale;
  const double q = uphill > 0.0 ? std::min(f, r) : std::max(f, r);
  // The line's point nearest to (ε, 1 − ε), then along the line (direction (−r, f)) to the
  // nearest point inside the square.
  const double norm = f * f + r * r;
  const double shift = (q - (epsilon * f + (1.0 - epsilon) * r)) / norm;
  const double front0 = epsilon + shift * f;
  const double rear0 = (1.0 - epsilon) + shift * r;
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();
  const auto keep_inside = [&](double start, double direction) {
    if (direction == 0.0) return;
    const double a = (0.0 - start) / direction;
    const double b = (1.0 - start) / direction;
    low = std::max(low, std::min(a, b));
    high = std::min(high, std::max(a, b));
  };
  keep_inside(front0, -r);
  keep_inside(rear0, f);
  // low ≤ high but for rounding where the line only touches a corner of the square.
  const double t = low <= high ? std::clamp(0.0, low, high) : 0.5 * (low + high);
  return {std::clamp(front0 - t * r, 0.0, 1.0), std::clamp(rear0 + t * f, 0.0, 1.0)};
}

ExteriorAxleVelocities exterior_axle_velocities(const AxleDistanceRates& rates,
                                                const AxleFactors& factors) {
  constexpr std::string_view kWhere = "exterior_axle_velocities";
  checks::law::require_finite(rates.front_mps, kWhere, "rates.front_mps (yf)");
  checks::law::require_finite(rates.rear_mps, kWhere, "rates.rear_mps (yr)");
  checks::law::require_finite(factors.front, kWhere, "factors.front (ρf)");
  checks::law::require_finite(factors.rear, kWhere, "factors.rear (ρr)");
  const double q = factors.front * rates.front_mps + factors.rear * rates.rear_mps;
  return {rates.rear_mps - q, rates.front_mps - q};
}

}  // namespace marsokhod::mobility
