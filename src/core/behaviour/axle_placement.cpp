#include "core/behaviour/axle_placement.hpp"

#include <algorithm>
#include <cmath>

#include "core/checks/checks.hpp"

namespace marsokhod::behaviour {
namespace {

constexpr const char* kFunction = "next_axle_placement";

void require_inputs(const AxlePlacementState& state, double requested_placement,
                    double joint_load_radps, double joint_velocity_radps,
                    const AxleResistance& axles, double period_s, const BehaviourParams& params) {
  checks::require_within(state.switch_fraction, 0.0, 1.0, kFunction, "state.switch_fraction");
  checks::require_non_negative(state.held_s, kFunction, "state.held_s");
  checks::require_within(requested_placement, 0.0, 1.0, kFunction, "requested_placement");
  checks::require_finite_estimate(joint_load_radps, kFunction, "joint_load_radps");
  checks::require_finite_estimate(joint_velocity_radps, kFunction, "joint_velocity_radps");
  checks::require_finite_estimate(axles.exterior_radps, kFunction, "axles.exterior_radps");
  checks::require_finite_estimate(axles.interior_radps, kFunction, "axles.interior_radps");
  checks::require_positive(period_s, kFunction, "period_s");
  checks::require_positive(params.axle_placement_load_radps, kFunction,
                           "params.axle_placement_load_radps");
  checks::require_positive(params.axle_placement_speed_radps, kFunction,
                           "params.axle_placement_speed_radps");
  checks::require_positive(params.axle_placement_rate_per_s, kFunction,
                           "params.axle_placement_rate_per_s");
  checks::require_non_negative(params.axle_placement_hold_s, kFunction,
                               "params.axle_placement_hold_s");
}

double blend(double fraction, double requested_placement) {
  return (1.0 - fraction) * requested_placement + fraction * (1.0 - requested_placement);
}

}  // namespace

double axle_resistance_radps(double left_load_radps, double left_drive_radps,
                             double right_load_radps, double right_drive_radps,
                             const BehaviourParams& params) {
  constexpr const char* kResistance = "axle_resistance_radps";
  checks::require_finite_estimate(left_load_radps, kResistance, "left_load_radps");
  checks::require_finite_estimate(left_drive_radps, kResistance, "left_drive_radps");
  checks::require_finite_estimate(right_load_radps, kResistance, "right_load_radps");
  checks::require_finite_estimate(right_drive_radps, kResistance, "right_drive_radps");
  checks::require_positive(params.axle_placement_speed_radps, kResistance,
                           "params.axle_placement_speed_radps");
  // A wheel stopped though driven: ν at least the speed threshold, w = l + ν under it.
  const auto held_back = [&](double load_radps, double drive_radps) {
    const bool driven = std::abs(drive_radps) >= params.axle_placement_speed_radps;
    const bool stopped = std::abs(load_radps + drive_radps) < params.axle_placement_speed_radps;
    if (!driven || !stopped) {
      return 0.0;
    }
    return drive_radps > 0.0 ? -load_radps : load_radps;
  };
  return std::min(held_back(left_load_radps, left_drive_radps),
                  held_back(right_load_radps, right_drive_radps));
}

AxlePlacementStep next_axle_placement(const AxlePlacementState& state, double requested_placement,
                                      double joint_load_radps, double joint_velocity_radps,
                                      const AxleResistance& axles, double period_s,
                                      const BehaviourParams& params,
                                      const BehaviourSwitches& switches) {
  require_inputs(state, requested_placement, joint_load_radps, joint_velocity_radps, axles,
                 period_s, params);
  if (!switches.axle_placement) {
    return AxlePlacementStep{AxlePlacementState{}, requested_placement};
  }
  const bool loaded = std::abs(joint_load_radps) > params.axle_placement_load_radps;
  const bool slow = std::abs(joint_velocity_radps) < params.axle_placement_speed_radps;
  const bool driven = std::abs(joint_velocity_radps - joint_load_radps) >=
                      params.axle_placement_speed_radps;  // |ν| = |w − l|
  // The axle ρ moves, held back (the header's "engage"): weighted by the present placement.
  const double moving = blend(state.switch_fraction, requested_placement);
  const bool moving_axle_held = driven && moving * axles.exterior_radps +
                                                  (1.0 - moving) * axles.interior_radps >
                                              params.axle_placement_load_radps;
  AxlePlacementState next = state;
  next.held_s = !state.switched && moving_axle_held ? state.held_s + period_s : 0.0;
  const bool held_long = moving_axle_held && next.held_s >= params.axle_placement_hold_s;
  if (!state.switched && (loaded || held_long)) {
    next.switched = true;
    next.held_s = 0.0;
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
  return AxlePlacementStep{next,
                           std::clamp(blend(next.switch_fraction, requested_placement), 0.0, 1.0)};
}

}  // namespace marsokhod::behaviour
