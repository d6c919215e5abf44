// Chapter 6.2.1 slant response: on a slope, extend the joint that faces downhill.
//
// At the start of every cycle the joint bounds are reset to (5.3); then
//   σ ≥ 0 (uphill, nose up):    p7_min = γ(σ)    (the rear joint faces downhill)         (6.4)
//   σ < 0 (downhill, nose down): p6_max = −γ(σ)   (the front joint faces downhill)
// each clipped into its (5.3) interval, so the bounds never leave (5.3) and min ≤ max. The
// control (4.16) then drives a joint that violates its new bound back into the feasible region.
//
// γ(σ) is the joint angle at which the downhill lever (joint to exterior axle, length a) hangs
// parallel to gravity. In the triangle of the lever a, the segment b (center axle to joint) and
// the axle distance c = sqrt(a² + b² − 2ab cos γ), the angle β at the exterior axle has
// cos β = (a − b cos γ)/c; the lever is vertical when β = π/2 ± σ, the thesis' relation
//   a − b cos γ = −c sin σ.
// Squaring it gives b² x² + 2ab s x − a² s − b² sin²σ = 0 for x = cos γ, s = −1 + sin²σ, with
// the two roots x = −(1/b)(a s ± sqrt((a² s + b²) sin²σ)). The printed formula
//   γ(σ) = acos( −(1/b)(a s + sqrt((a² s + b²) sin²σ)) )
// takes the root with a − b cos γ ≥ 0, which satisfies the relation for σ ≤ 0: the front joint
// on a descent, written in the front joint's frame. The formula is even in σ; for σ > 0 it
// satisfies the mirrored relation a − b cos γ = +c sin σ of the rear lever, which on an ascent
// is the downhill one. (The other root solves the printed relation for σ > 0, but it is a
// contracted angle below acos(a/b), which (5.3) would clip away.) So the printed formula is
// right as used in (6.4): the downhill joint's angle, a − b cos γ(σ) = c |sin σ|, with
// γ(0) = acos(a/b) = 1.21206 rad (the contracted bound of (5.3), 1.2121 rounded) and
// γ(15°) = 1.48661 rad.
#pragma once

#include "core/behaviour/switches.hpp"
#include "core/params.hpp"

namespace marsokhod::behaviour {

// The joint position bounds of (4.16) for the front joint (p6) and the rear joint (p7) [rad].
struct JointBounds {
  double front_min_rad = 0.0;  // p6_min
  double front_max_rad = 0.0;  // p6_max
  double rear_min_rad = 0.0;   // p7_min
  double rear_max_rad = 0.0;   // p7_max
};

// The bounds (5.3) as configured. Throws std::invalid_argument if a bound is not finite or a
// minimum exceeds its maximum.
JointBounds joint_bounds_of(const JointParams& joints);

// γ(σ) [rad] in (0, π] for any finite slope σ [rad], from a = joint_to_exterior_axle_m and
// b = center_axle_to_joint_m. Throws std::invalid_argument if σ is not finite or not 0 < a < b.
double gravity_parallel_joint_angle_rad(double slope_rad, const GeometryParams& geometry);

// (6.4): the bounds for this cycle on a slope σ [rad]; the bounds (5.3) when the slant response
// is switched off. Throws std::invalid_argument as the two functions above.
JointBounds slant_joint_bounds(double slope_rad, const JointParams& joints,
                               const GeometryParams& geometry, const BehaviourSwitches& switches);

}  // namespace marsokhod::behaviour
