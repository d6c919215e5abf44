// (4.15) time-optimal position and velocity control: reach the state (v_d, p_d) in least time.
//
// Under c = C·sgn(v_d − v) the velocity reaches v_d after T = (1/μ)·log((c − v)/(c − v_d)) s,
// at the position
//   p_T = p + (1/μ)·(v − v_d + c·log((c − v)/(c − v_d)))     [u]   (Lemma 4.15)
// The states with p_T = p_d form the switching curve Γ through (v_d, p_d) (Figure 4.9). The
// thesis' law is
//   c^k = 𝒞(v_d, p_d) = C·sgn(p_d − p_T(v^k, p^k))                                    (4.15)
// which, in continuous time, drives with ±C to Γ and then along Γ into the target: one switch,
// the least time.
//
// Edges, decided here:
// - v is clamped to [−C, C] and v_d to ±(1 − 1e-9)·C before p_T is evaluated. The logarithm
//   needs (c − v)/(c − v_d) > 0, i.e. |v_d| < C (v_d = ±C is reached only after infinite time)
//   and |v| ≤ C (a measured |v| slightly above C is treated as C).
// - v = v_d makes c = C·sgn(0) = 0 and the log term 0·log 1: p_T = p. sgn(0) = 0.
// - NaN or infinite inputs are rejected with std::invalid_argument; no NaN is ever returned.
//
// Sampled at period h, the pure sign law chatters between ±C around Γ and around the target:
// the state crosses Γ inside a period and the law only notices at the next one.
// position_velocity_control() therefore refines it with two rules that act only within one or
// two periods of Γ or of the target; elsewhere it returns exactly the thesis' ±C:
// 1. Terminal step. If (v_d, p_d) can be reached exactly in two periods with |c^k|, |c^(k+1)| ≤ C
//    under (4.12)/(4.13) (two_step_controls), return that c^k: from there no sampled law is
//    faster (unless one period happens to suffice), and with v_d = 0 the state then stays at
//    the target with c = 0 (it settles instead of chattering). The price: p may pass p_d in
//    between by at most about μC·h²/16 (8.6e-6 rad for the joints at 64 Hz); use (4.16) where
//    a position must never be passed.
// 2. Landing on Γ. If the sign law's ±C would carry the next state across Γ (p_d − p_T changes
//    sign), return instead the c ∈ [−C, C] nearest to that ±C whose next state stays on this
//    side of Γ or on it (bisection): the state lands on Γ. A state on Γ (|p_d − p_T| within
//    1e-12 of |p| + |p_d| + C/μ, i.e. up to rounding) follows its arc with C·sgn(v_d − v), as
//    in continuous time. If every c crosses Γ, the end (±C) nearer to Γ is returned.
// The result is within two periods of the continuous-time least time of the lemma (tested on
// a grid of states). With v_d ≠ 0 the target is a state passed through, not one to stay in:
// the sampled state passes it within one period's travel |v_d|·h and one period's full
// acceleration 2μC·h; the law is memoryless and then turns back toward it, so a caller
// switches targets once reached. At the target exactly the law returns c = v_d (holds
// v = v_d; for the usual v_d = 0 this is the thesis' C·sgn(0) = 0).
#pragma once

#include "core/control/control_params.hpp"
#include "core/control/motion_model.hpp"

namespace marsokhod::control {

// p_T of Lemma 4.15 [u]: where the velocity reaches v_d under c = C·sgn(v_d − v), with the
// clamps above.
double position_when_velocity_reached(const MotionState& state, double target_velocity,
                                      const ControlParams& params);

// (4.15) as printed: C·sgn(p_d − p_T) ∈ {−C, 0, C}. Chatters when sampled; kept for comparison.
double bang_bang_position_velocity_control(const MotionState& state, const MotionState& target,
                                           const ControlParams& params);

// (4.15) with the two sampled-time refinements above; returns c ∈ [−C, C].
double position_velocity_control(const MotionState& state, const MotionState& target,
                                 const ControlParams& params);

}  // namespace marsokhod::control
