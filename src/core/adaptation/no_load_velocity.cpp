#include "core/adaptation/no_load_velocity.hpp"

#include <cmath>

#include "core/checks/checks.hpp"

namespace marsokhod::adaptation {
namespace {

void check_scaling(const char* function, double zeta, double supply_v, double nominal_supply_v) {
  checks::require_positive(zeta, function, "zeta");
  checks::require_positive(supply_v, function, "supply_v");
  checks::require_positive(nominal_supply_v, function, "nominal_supply_v");
}

}  // namespace

double no_load_velocity(const MotorCurve& curve, double duty, double zeta, double supply_v,
                        double nominal_supply_v) {
  checks::require_finite(duty, "no_load_velocity", "duty");
  check_scaling("no_load_velocity", zeta, supply_v, nominal_supply_v);
  const double w_hat_radps = zeta * curve.velocity_radps(duty) * (supply_v / nominal_supply_v);
  checks::require_finite_result(w_hat_radps, "no_load_velocity", "zeta * W(duty) * U/U_nominal");
  return w_hat_radps;
}

double duty_for_no_load_velocity(const MotorCurve& curve, double w_hat_radps, double zeta,
                                 double supply_v, double nominal_supply_v) {
  checks::require_finite(w_hat_radps, "duty_for_no_load_velocity", "w_hat_radps");
  check_scaling("duty_for_no_load_velocity", zeta, supply_v, nominal_supply_v);
  // The quotient can overflow to ±inf for a tiny zeta or supply_v; W⁻¹ would then reject it, so
  // saturate here as the header promises.
  const double normalized_radps = w_hat_radps / zeta * (nominal_supply_v / supply_v);
  if (!std::isfinite(normalized_radps)) {
    return normalized_radps > 0.0 ? 1.0 : -1.0;
  }
  return curve.duty(normalized_radps);
}

double passive_duty(const MotorCurve& curve, double measured_velocity_radps, double zeta,
                    double supply_v, double nominal_supply_v) {
  checks::require_finite(measured_velocity_radps, "passive_duty", "measured_velocity_radps");
  check_scaling("passive_duty", zeta, supply_v, nominal_supply_v);
  return duty_for_no_load_velocity(curve, measured_velocity_radps, zeta, supply_v,
                                   nominal_supply_v);
}

}  // namespace marsokhod::adaptation
