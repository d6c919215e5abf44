#include "core/control/velocity_control.hpp"

#include <algorithm>

#include "core/checks/checks.hpp"

namespace marsokhod::control {

double velocity_control(double velocity, double target_velocity, const ControlParams& params) {
  constexpr std::string_view kLaw = "velocity_control (4.14)";
  validate(params);
  checks::law::require_finite(velocity, kLaw, "velocity");
  checks::law::require_finite(target_velocity, kLaw, "target_velocity");
  const double step_rate = params.period_s * params.rate_per_s;  // hμ
  const double control = (target_velocity - (1.0 - step_rate) * velocity) / step_rate;
  return std::clamp(control, -params.max_speed, params.max_speed);
}

}  // namespace marsokhod::control
