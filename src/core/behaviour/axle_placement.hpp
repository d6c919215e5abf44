// Chapter 6.2.3 placement of the exterior axle: when an obstacle keeps the joint from moving
// the exterior axle, ρ (ρf, ρr of (5.1), (5.2)) is switched to 1 − ρ, so that the joint bends
// by moving the rest of the rover instead ("the robot backs up to facilitate the bending").
//
// One state machine per joint, fed every cycle with the ρ the operator or the gait asks for,
// the joint motor's load l and velocity w [rad/s] and the period h [s]. With l = w − ν (4.4),
// ν = w − l is the velocity the joint is driven at.
//   engage:  unswitched and |l| > axle_placement_load_radps (the joint pushes against a
//            hindrance) → switched.
//   release: switched, |l| ≤ axle_placement_load_radps, and both |w| and |ν| = |w − l| below
//            axle_placement_speed_radps: the joint has stopped and is no longer driven, so the
//            bending that the switch made possible is over (target reached, or the operator let
//            go) → unswitched.
// The output blends the two placements with the switch fraction f ∈ [0, 1]:
//   ρ_out = (1 − f) ρ + f (1 − ρ),
// and f moves toward 1 while switched and toward 0 while unswitched: at once while the joint
// is slow (|w| < axle_placement_speed_radps, so the jump in the sum (5.4) is small, the thesis'
// argument), otherwise by at most axle_placement_rate_per_s · h per cycle, so ρ_out moves at
// most that fast. Unswitched with f = 0, ρ_out is exactly the requested ρ, so a requested ρ
// that changes every cycle (docs/design.md's ε-formula) passes through without lag. Since a release
// needs a slow joint, the return to ρ is immediate; the gradual path serves an engagement while
// the joint moves fast.
//
// Why the release waits for the joint to stop and its drive to end rather than only for the
// load to fall: once switched, the joint bends freely and its load drops while the joint is
// still slow, accelerating. Releasing then would restore ρ, press the axle against the
// obstacle again and re-engage: the switch would chatter at the cycle rate, or ρ would hover
// where the load meets the threshold. Switched and loaded again (the rover cannot back up
// either), the switch holds; (4.16) and the operator decide what happens next.
#pragma once

#include "core/behaviour/switches.hpp"
#include "core/params.hpp"

namespace marsokhod::behaviour {

// What one joint's axle placement carries from cycle to cycle; default: unswitched.
struct AxlePlacementState {
  bool switched = false;
  double switch_fraction = 0.0;  // f: 0 = ρ as requested, 1 = 1 − ρ
};

struct AxlePlacementStep {
  AxlePlacementState state;
  double placement = 0.0;  // ρ_out ∈ [0, 1], for (5.1), (5.2)
};

// One cycle of the state machine above. With the behaviour switched off ρ_out is the requested
// ρ and the state returns to unswitched. Throws std::invalid_argument if the requested ρ or the
// state's f is outside [0, 1], an input is not finite, h is not > 0, or a threshold or rate in
// BehaviourParams is not > 0.
AxlePlacementStep next_axle_placement(const AxlePlacementState& state, double requested_placement,
                                      double joint_load_radps, double joint_velocity_radps,
                                      double period_s, const BehaviourParams& params,
                                      const BehaviourSwitches& switches);

}  // namespace marsokhod::behaviour
