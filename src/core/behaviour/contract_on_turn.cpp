#include "core/behaviour/contract_on_turn.hpp"

#include <algorithm>
#include <cmath>

#include "core/checks/checks.hpp"

namespace marsokhod::behaviour {

JointVelocityTargets contract_joints_when_turning(const JointVelocityTargets& targets,
                                                  double spin_target_radps,
                                                  double max_no_load_speed_radps, double max_abs_n6,
                                                  double max_abs_n7,
                                                  const BehaviourSwitches& switches) {
  constexpr const char* kFunction = "contract_joints_when_turning";
  checks::require_finite_estimate(targets.front_radps, kFunction, "targets.front_radps");
  checks::require_finite_estimate(targets.rear_radps, kFunction, "targets.rear_radps");
  checks::require_finite_estimate(spin_target_radps, kFunction, "spin_target_radps");
  checks::require_positive(max_no_load_speed_radps, kFunction, "max_no_load_speed_radps");
  checks::require_positive(max_abs_n6, kFunction, "max_abs_n6");
  checks::require_positive(max_abs_n7, kFunction, "max_abs_n7");
  if (!switches.contract_on_turn) {
    return targets;
  }
  const double front_limit_radps = max_no_load_speed_radps / max_abs_n6;  // v̄6
  const double rear_limit_radps = max_no_load_speed_radps / max_abs_n7;   // v̄7
  const double spin_radps = std::abs(spin_target_radps);
  return JointVelocityTargets{
      std::clamp(targets.front_radps + spin_radps, -front_limit_radps, front_limit_radps),
      std::clamp(targets.rear_radps - spin_radps, -rear_limit_radps, rear_limit_radps)};
}

}  // namespace marsokhod::behaviour
