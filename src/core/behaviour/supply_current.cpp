#include "core/behaviour/supply_current.hpp"

#include <algorithm>
#include <cmath>

#include "core/checks/checks.hpp"

namespace marsokhod::behaviour {

double motor_current_bound_a(double duty, double shaft_velocity_radps, double supply_v,
                             const SupplyCurrentParams& params) {
  constexpr const char* kFunction = "motor_current_bound_a";
  checks::require_within(duty, -1.0, 1.0, kFunction, "duty");
  checks::require_finite(shaft_velocity_radps, kFunction, "shaft_velocity_radps");
  checks::require_finite(supply_v, kFunction, "supply_v");
  checks::require_non_negative(supply_v, kFunction, "supply_v");
  if (duty == 0.0) return 0.0;
  // The stall torque at a bridge voltage: above the dead zone's, at least the holding torque.
  const auto stall_at_nm = [&](double volts) {
    return std::max(params.motor_holding_torque_nm,
                    params.motor_stall_torque_per_v_nm *
                        std::max(0.0, volts - params.motor_dead_zone_v));
  };
  double stall_nm = stall_at_nm(std::abs(duty) * supply_v);
  if (duty * shaft_velocity_radps < 0.0) {  // plugging: the back-EMF adds to the bridge's voltage
    const double back_emf_nm =
        std::abs(shaft_velocity_radps) / params.motor_plugging_droop_radps_per_nm;
    // At most the full-duty stall torque, never below the duty's (|d| ≤ 1).
    stall_nm = std::min(stall_at_nm(supply_v), stall_nm + back_emf_nm);
  }
  return params.motor_no_load_current_a +
         params.motor_current_per_radps_a * std::abs(shaft_velocity_radps) +
         std::abs(duty) * stall_nm / params.motor_torque_constant_nm_per_a;
}

}  // namespace marsokhod::behaviour
