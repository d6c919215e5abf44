// Chapter 6.2.3 placement of the exterior axle: when an obstacle keeps the joint from moving
// the exterior axle, ρ (ρf, ρr of (5.1), (5.2)) is switched to 1 − ρ, so that the joint bends
// by moving the rest of the rover instead ("the robot backs up to facilitate the bending").
//
// One state machine per joint, fed every cycle with the ρ the operator or the gait asks for,
// the joint motor's load l and velocity w [rad/s] and the period h [s]. With l = w − ν (4.4),
// ν = w − l is the velocity the joint is driven at.
//   engage:  unswitched and |l| > axle_placement_load_radps (the joint pushes against a
//            hindrance) → switched. Also unswitched, and for axle_placement_hold_s on end the
//            joint driven (|ν| ≥ axle_placement_speed_radps) and the axle ρ moves held back by
//            more than axle_placement_load_radps (below) → switched.
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
// The axle ρ moves: ρ = 1 moves the exterior axle (front for the front joint, rear for the
// rear one), ρ = 0 the interior side, whose axle next to the joint is the centre axle. How hard
// it is held back is ρ_now · r_ext + (1 − ρ_now) · r_int, ρ_now the placement the state's f
// makes of ρ, r an axle's resistance (axle_resistance_radps): how much slower than driven its
// wheels turn, once both have stopped. Our extension of the thesis' rule, which reads the joint alone: the anchors track
// their (5.1) commands open loop, and those follow the joint's assigned velocity, not its
// measured one. When the obstacle stops the moving axle, the anchor then gives way instead: it
// rolls toward the joint, the joint still turns at a fraction of its command, and its load stays
// under the threshold, while the moving axle's wheels stall pushing against the obstacle
// (front-wheel walking's contraction with the centre wheels at the block's face). Switching ρ
// then moves the anchor on purpose and stands the stalled axle, as the thesis' rule would. The
// hold time (0.5 s) lets pass what stops an axle for a few cycles, a stroke's start: its drive
// steps up to 0.6 rad/s while the wheels still stand, and they follow within about 60 ms (grass
// rolking's rear wheels). It is a tenth of the stuck failsafe's 5 s, which a stalled centre
// axle would otherwise reach.
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
  double held_s = 0.0;           // how long the axle ρ moves has been held back, unswitched
};

// How hard the axles on the two sides of a joint are held back [rad/s], for the engage rule.
struct AxleResistance {
  double exterior_radps = 0.0;  // the front axle for the front joint, the rear for the rear one
  double interior_radps = 0.0;  // the centre axle
};

struct AxlePlacementStep {
  AxlePlacementState state;
  double placement = 0.0;  // ρ_out ∈ [0, 1], for (5.1), (5.2)
};

// An axle's resistance from its two wheels' loads l = w − ν (4.4) and drive velocities ν
// [rad/s]: how much slower than driven a stopped axle turns. A wheel stopped though driven
// (|ν| ≥ axle_placement_speed_radps, |w| = |l + ν| < axle_placement_speed_radps) gives
// −sgn(ν) · l, any other wheel 0, and the axle the smaller of its two wheels' figures: it has
// stopped only if both have. A wheel that merely lags its drive (a stroke's start, a heavy
// load) or one wheel that cannot turn (broken-wheel-walking's rigid wheel, dragged by the
// gait) is no obstacle. Throws std::invalid_argument if an input is not finite or the speed
// threshold is not > 0.
double axle_resistance_radps(double left_load_radps, double left_drive_radps,
                             double right_load_radps, double right_drive_radps,
                             const BehaviourParams& params);

// One cycle of the state machine above. With the behaviour switched off ρ_out is the requested
// ρ and the state returns to unswitched. Throws std::invalid_argument if the requested ρ or the
// state's f is outside [0, 1], its held_s or the hold time is negative, an input is not finite,
// h is not > 0, or a threshold or rate in BehaviourParams is not > 0.
AxlePlacementStep next_axle_placement(const AxlePlacementState& state, double requested_placement,
                                      double joint_load_radps, double joint_velocity_radps,
                                      const AxleResistance& axles, double period_s,
                                      const BehaviourParams& params,
                                      const BehaviourSwitches& switches);

}  // namespace marsokhod::behaviour
