#include "core/behaviour/load_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "core/checks/checks.hpp"

namespace marsokhod::behaviour {
namespace {

void require_inputs(const MotorVector& loads_radps, double drive_speed_radps,
                    const LoadDistributionParams& params, const char* function) {
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    checks::require_finite_estimate(loads_radps[i], function,
                                    checks::Element{"loads_radps", i});
  }
  checks::require_finite_estimate(drive_speed_radps, function, "drive_speed_radps");
  checks::require_non_negative(params.gain_per_radps, function, "params.gain_per_radps");
  checks::require_positive(params.max_correction_radps, function, "params.max_correction_radps");
}

double mean_wheel_load_radps(const MotorVector& loads_radps) {
  double sum = 0.0;
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    sum += loads_radps[i];
  }
  return sum / static_cast<double>(kWheelCount);
}

// Removes the rounding left in Σ h, then scales h by one factor so that max |h_i| ≤ H. Each
// element is H · (h_i / max), so the largest is exactly ±H and none can round above H.
MotorVector sum_preserving_clip(MotorVector correction, double max_correction_radps,
                                const char* function) {
  double sum = 0.0;
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    sum += correction[i];
  }
  if (!std::isfinite(sum)) {
    throw std::invalid_argument(std::string(function) +
                                ": the correction overflowed; the wheel loads are far outside "
                                "any physical range (|l| of a few rad/s), check their estimate");
  }
  double largest = 0.0;
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    correction[i] -= sum / static_cast<double>(kWheelCount);
    largest = std::max(largest, std::abs(correction[i]));
  }
  if (largest > max_correction_radps) {
    for (std::size_t i = 0; i < kWheelCount; ++i) {
      correction[i] = max_correction_radps * (correction[i] / largest);
    }
  }
  correction[kFrontJoint] = 0.0;
  correction[kRearJoint] = 0.0;
  return correction;
}

}  // namespace

MotorVector variance_load_distribution_radps(const MotorVector& loads_radps,
                                             double drive_speed_radps,
                                             const LoadDistributionParams& params) {
  require_inputs(loads_radps, drive_speed_radps, params, "variance_load_distribution_radps");
  if (drive_speed_radps == 0.0) {
    return MotorVector{};
  }
  const double mean_radps = mean_wheel_load_radps(loads_radps);
  double square_sum = 0.0;
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    square_sum += (loads_radps[i] - mean_radps) * (loads_radps[i] - mean_radps);
  }
  const double deviation_radps = std::sqrt(square_sum / static_cast<double>(kWheelCount - 1));
  MotorVector correction{};
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    correction[i] = params.gain_per_radps * (mean_radps - loads_radps[i]) * deviation_radps;
  }
  return sum_preserving_clip(correction, params.max_correction_radps,
                             "variance_load_distribution_radps");
}

MotorVector slip_load_distribution_radps(const MotorVector& loads_radps, double drive_speed_radps,
                                         const LoadDistributionParams& params) {
  require_inputs(loads_radps, drive_speed_radps, params, "slip_load_distribution_radps");
  if (drive_speed_radps == 0.0) {
    return MotorVector{};
  }
  const double mean_radps = mean_wheel_load_radps(loads_radps);
  MotorVector product{};  // (l̄ − l_i) l_i
  double product_sum = 0.0;
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    product[i] = (mean_radps - loads_radps[i]) * loads_radps[i];
    product_sum += product[i];
  }
  const double product_mean = product_sum / static_cast<double>(kWheelCount);
  const double direction = drive_speed_radps > 0.0 ? 1.0 : -1.0;  // sgn v1
  MotorVector correction{};
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    correction[i] = params.gain_per_radps * (product_mean - product[i]) * direction;
  }
  return sum_preserving_clip(correction, params.max_correction_radps,
                             "slip_load_distribution_radps");
}

MotorVector load_distribution_radps(const MotorVector& loads_radps, double drive_speed_radps,
                                    const LoadDistributionParams& params,
                                    const BehaviourSwitches& switches) {
  switch (switches.load_distribution) {
    case LoadDistributionMode::kVariance:
      return variance_load_distribution_radps(loads_radps, drive_speed_radps, params);
    case LoadDistributionMode::kSlip:
      return slip_load_distribution_radps(loads_radps, drive_speed_radps, params);
    case LoadDistributionMode::kOff:
      break;
  }
  require_inputs(loads_radps, drive_speed_radps, params, "load_distribution_radps");
  return MotorVector{};
}

}  // namespace marsokhod::behaviour
