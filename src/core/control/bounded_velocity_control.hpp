// (4.16) velocity control with bounded position: reach and hold v_d while p_min ≤ p ≤ p_max.
//
//   c^k = 𝒞(v_d, p_min, p_max) = clip(𝒞(0, p_min), 𝒞(v_d), 𝒞(0, p_max))                (4.16)
//
// with 𝒞(v_d) the velocity control (4.14) and clip(a, b, c) = min(max(a, b), c). Units: p in u,
// v and c in u/s.
//
// In the thesis 𝒞(0, p_max) is (4.15) toward (0, p_max): ±C, switching where braking with −C
// stops exactly at p_max. Sampled at period h that switch comes up to one period late, so p
// would pass p_max and then chatter around it. Here the bound terms are their non-crossing
// sampled form instead:
//   upper_bound_control = the largest c ∈ [−C, C] whose next state (4.12)/(4.13) can still stop
//                         at or below p_max by braking with −C (its highest reach ≤ p_max);
//                         but when the two-period exact stop at (0, p_max) (two_step_controls)
//                         fits |c| ≤ C and also keeps the next state's highest reach ≤ p_max,
//                         its first control, so that the state comes to rest exactly on the
//                         bound (c = 0 there) instead of creeping toward it;
//   lower_bound_control = the same for p_min, mirrored (p → −p).
// Far from a bound they return ±C, exactly as the thesis' terms do there, so (4.16) returns
// (4.14). Near a bound the clip rides the braking curve into it and then rests on it. If
// p_min ≤ p^0 ≤ p_max and the start can still stop inside, every sample p^k stays in
// [p_min, p_max] for ever, also in floating point (the highest reach is max(p, stop point), so
// it bounds p itself). Between samples the continuous p of (4.10) may pass the bound in the
// one period in which v changes sign on arrival, by at most about μC·h²/20 (6.9e-6 rad for the
// joints at 64 Hz).
//
// Edges:
// - p_min = −∞ and/or p_max = +∞ switch that bound off; with both off (4.16) equals (4.14).
// - NaN bounds, p_min = +∞, p_max = −∞ or p_min > p_max are rejected (std::invalid_argument),
//   as are NaN or infinite states and target velocities.
// - A state that can no longer stop inside a bound (outside it, or too fast toward it) gets
//   −C from the upper term (+C from the lower one): back inside as fast as possible.
// - If the interval is too narrow for both terms (lower > upper), the upper bound wins, as in
//   the thesis' clip. Hence 𝒞(0, p_d, p_d) of the thesis' remark reaches p_d from below only;
//   use (4.15) to reach a position.
#pragma once

#include "core/control/control_params.hpp"
#include "core/control/motion_model.hpp"

namespace marsokhod::control {

// The sampled form of 𝒞(0, p_max) described above; max_position may be +∞ (then C).
double upper_bound_control(const MotionState& state, double max_position,
                           const ControlParams& params);

// The sampled form of 𝒞(0, p_min) described above; min_position may be −∞ (then −C).
double lower_bound_control(const MotionState& state, double min_position,
                           const ControlParams& params);

// (4.16): the control c ∈ [−C, C] for v_d [u/s] within [min_position, max_position] [u].
double bounded_velocity_control(const MotionState& state, double target_velocity,
                                double min_position, double max_position,
                                const ControlParams& params);

}  // namespace marsokhod::control
