#include "core/control/control_params.hpp"

#include "core/checks/checks.hpp"

namespace marsokhod::control {

void validate(const ControlParams& params) {
  constexpr std::string_view kLaw = "ControlParams";
  checks::law::require_positive(params.rate_per_s, kLaw,
                                "rate_per_s (μ of (4.9); e.g. 0.4 for the joints)");
  checks::law::require_positive(params.max_speed, kLaw, "max_speed (C, the bound |c| ≤ C)");
  checks::law::require_positive(params.period_s, kLaw,
                                "period_s (h, the cycle period; 0.0156 at 64 Hz)");
}

ControlParams joint_control_params(const Params& params) {
  const ControlParams control{
      params.joints.control_rate_per_s,
      params.joints.control_speed_fraction * params.motors.max_no_load_speed_radps,
      params.cycle.period_s};
  validate(control);
  return control;
}

}  // namespace marsokhod::control
