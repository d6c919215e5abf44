// Chapter 6.2.2: contract the joints while the rover turns, because a shorter wheel base turns
// more efficiently (Procedure 5.1). The joint target velocities of the operator or the gait
// are modified to
//   v6ᵈ := clip(−v̄6, v6ᵈ + |v2ᵈ|, v̄6),   v7ᵈ := clip(−v̄7, v7ᵈ − |v2ᵈ|, v̄7)
// with v̄6 = w / max|n6|, v̄7 = w / max|n7| and clip(a, b, c) = min(max(a, b), c).
//
// Signs: p6 = −γf and p7 = +γr, and a joint contracts as its γ falls toward acos(a/b). The front
// joint contracts with p6 rising toward −acos(a/b), i.e. v6 > 0; the rear one with p7 falling
// toward +acos(a/b), i.e. v7 < 0; hence +|v2ᵈ| for 6 and −|v2ᵈ| for 7, whichever way the rover
// spins. The bounds (5.3) in (4.16) stop the contraction at the contracted pose. v̄ is the joint
// speed at which the fastest wheel accompanying the joint (n6, n7 of chapter 5.3, passed in
// from the mobility geometry) reaches the no-load speed w, so the wheels can follow.
#pragma once

#include "core/behaviour/switches.hpp"

namespace marsokhod::behaviour {

// v6ᵈ, v7ᵈ [rad/s].
struct JointVelocityTargets {
  double front_radps = 0.0;  // v6ᵈ
  double rear_radps = 0.0;   // v7ᵈ
};

// The targets with the turning contribution of the spin target v2ᵈ [rad/s]; w [rad/s] is
// MotorParams::max_no_load_speed_radps, max_abs_n6 and max_abs_n7 the largest |entry| of n6,
// n7 (wheel speed per joint speed). Unchanged when the behaviour is switched off. Throws
// std::invalid_argument if an input is not finite or w, max|n6|, max|n7| is not > 0.
JointVelocityTargets contract_joints_when_turning(const JointVelocityTargets& targets,
                                                  double spin_target_radps,
                                                  double max_no_load_speed_radps, double max_abs_n6,
                                                  double max_abs_n7,
                                                  const BehaviourSwitches& switches);

}  // namespace marsokhod::behaviour
