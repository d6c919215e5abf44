#include "core/behaviour/axle_placement.hpp"

#include <algorithm>
#include <cmath>

#include "core/checks/checks.hpp"

namespace marsokhod::behaviour {
namespace {

constexpr const char* kFunction = "next_axle_placement";

void require_inputs(const AxlePlacementState& state, double requested_placement,
                    double joint_load_radps, double joint_velocity_radps, double period_s,
                    const BehaviourParams& params) {
  checks::require_within(state.switch_fraction, 0.0, 1.0, kFunction, "state.switch_fraction");
  checks::require_within(requested_placement, 0.0, 1.0, kFunction, "requested_placement");
  checks::require_finite_estimate(joint_load_radps, kFunction, "joint_load_radps");
  checks::require_finite_estimate(joint_velocity_radps, kFunction, "joint_velocity_radps");
  checks::require_positive(period_s, kFunction, "period_s");
  checks::require_positive(params.axle_placement_load_radps, kFunction,
                           "params.axle_placement_load_radps");
  checks::require_positive(params.axle_placement_speed_radps, kFunction,
                           "params.axle_placement_speed_radps");
  checks::require_positive(params.axle_placement_rate_per_s, kFunction,
                           "params.axle_placement_rate_per_s");
}

}  // namespace

AxlePlacementStep next_axle_placement(const AxlePlacementState& state, double requested_placement,
                                      double joint_load_radps, double joint_velocity_radps,
                                      double period_s, const BehaviourParams& params,
                                      const BehaviourSwitches& switches) {
  require_inputs(state, requested_placement, joint_load_radps, joint_velocity_radps, period_s,
                 params);
  if (!switches.axle_placement) {
    return AxlePlacementStep{AxlePlacementState{}, requested_placement};
  }
  const bool loaded = std::abs(joint_load_radps) > params.axle_placement_load_radps;
  const bool slow = std::abs(joint_velocity_radps) < params.axle_placement_speed_radps;
  const bool driven = std::abs(joint_velocity_radps - joint_load_radps) >=
                      params.axle_placement_speed_radps;  // |ν| = |w − l|
  AxlePlacementState next = state;
  if (!state.switched && loaded) {
    next.switched = true;
  } else if (state.switched && !loaded && slow && !driven) {
    next.switched = false;
  }
  const double target_fraction = next.switched ? 1.0 : 0.0;
  if (slow) {
    next.switch_fraction = target_fraction;
  } else {
    const double step = params.axle_placement_rate_per_s * period_s;
    next.switch_fraction =
        std::clamp(target_fraction, state.switch_fraction - step, state.switch_fraction + step);
  }
  const double placement = (1.0 - next.switch_fraction) * requested_placement +
                           next.switch_fraction * (1.0 - requested_placement);
  return AxlePlacementStep{next, std::clamp(placement, 0.0, 1.0)};
}

}  // namespace marsokhod::behaviour
