// (4.14) velocity control: reach and hold the velocity v_d.
//
//   c^k = 𝒞(v_d) = clip(−C, (v_d − (1 − hμ)·v^k) / (hμ), C)                         (4.14)
//
// with clip(a, b, c) = min(max(a, b), c). Units: v, v_d and c in u/s, h in s, μ in 1/s.
//
// This is the thesis' first-order form: it inverts the Euler step v' ≈ (1 − hμ)v + hμ·c. The
// exact discretisation (4.13) would give the deadbeat choice (v_d − v·e^(−hμ))/(1 − e^(−hμ)).
// Under (4.13) the unclipped (4.14) leaves the error v − v_d multiplied per period by
//   λ(hμ) = e^(−hμ) − (1 − e^(−hμ))(1 − hμ)/(hμ) ≈ hμ/2   (0.0031 at hμ = 0.00624),
// and 0 ≤ λ < 1 for every hμ > 0 (λ(1) = e^(−1)); so v converges to v_d monotonically, without
// overshoot, while the clipped steps move toward v_d at the full rate of (4.9).
//
// Edges: |v_d| > C is allowed and drives v to ±C; the output always lies in [−C, C]; a NaN or
// infinite v or v_d is rejected with std::invalid_argument naming the argument.
#pragma once

#include "core/control/control_params.hpp"

namespace marsokhod::control {

// (4.14): the control c ∈ [−C, C] for the velocity v [u/s] and the target velocity v_d [u/s].
double velocity_control(double velocity, double target_velocity, const ControlParams& params);

}  // namespace marsokhod::control
