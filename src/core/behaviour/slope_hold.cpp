#include "core/behaviour/slope_hold.hpp"

#include <algorithm>
#include <cmath>

#include "core/behaviour/slope_estimate.hpp"
#include "core/checks/checks.hpp"

namespace marsokhod::behaviour {

MotorVector SlopeHold::update(const MotorVector& velocity_radps, const MotorVector& planned_radps,
                              double slope_rad, bool gait_running, double period_s,
                              const BehaviourParams& params) {
  constexpr std::string_view kFunction = "SlopeHold::update";
  checks::require_finite(slope_rad, kFunction, "slope_rad (σ)");
  checks::require_positive(period_s, kFunction, "period_s (h)");
  checks::require_non_negative(params.slope_hold_gain_per_s, kFunction,
                               "params.slope_hold_gain_per_s (K)");
  checks::require_non_negative(params.slope_hold_max_rad, kFunction,
                               "params.slope_hold_max_rad (E)");
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    checks::require_finite(velocity_radps[i], kFunction, checks::Element{"velocity_radps", i});
    checks::require_finite(planned_radps[i], kFunction, checks::Element{"planned_radps", i});
  }
  MotorVector term{};
  const double uphill = uphill_side(slope_rad, params);
  if (!gait_running || params.slope_hold_gain_per_s <= 0.0 || uphill == 0.0) {
    lost_rad_ = {};
    return term;
  }
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    const double lost = lost_rad_[i] + period_s * uphill * (planned_radps[i] - velocity_radps[i]);
    lost_rad_[i] = std::clamp(lost, 0.0, params.slope_hold_max_rad);
    term[i] = uphill * params.slope_hold_gain_per_s * lost_rad_[i];
  }
  return term;
}

}  // namespace marsokhod::behaviour
