// Chapter 6.3 load distribution: while the rover drives (v1 ≠ 0), a correction h is added to
// the wheel control ŵ that shifts speed, and so power, between the six wheels by their loads
// l_0 … l_5 (l = w − ν: negative on a wheel that pushes against resistance, about 0 on one that
// spins free, positive on one that is dragged faster than its motor drives it). With
// l̄ = (1/6) Σ l_i and var(l) = (1/5) Σ (l_i − l̄)²:
//   h^v_i = clip(−H, 5 (l̄ − l_i) sqrt(var l), H)                                       (6.5)
//   h^s_i = clip(−H, 5 [mean_j((l̄ − l_j) l_j) − (l̄ − l_i) l_i] sgn v1, H)             (6.6)
// 5 = LoadDistributionParams::gain_per_radps, H = max_correction_radps.
//
// The clip: before clipping both terms sum to zero, so ŵ + h only redistributes ŵ, which is
// the point of (6.5) and (6.6). Clipping element by element breaks that as soon as one element
// is clipped (one stuck wheel: h = (1.09, −0.22 × 5) clips to (0.3, −0.22 × 5), sum −0.79).
// Here the whole vector is scaled by one factor instead, H / max_i |h_i| when that is below 1:
// Σ h_i = 0 and |h_i| ≤ H both hold, the pattern (which wheel gains, which loses, in what
// ratio) is kept, and whenever no element reaches H the result is exactly the thesis' clip.
// Before scaling, the vector's mean (rounding only) is subtracted, so Σ h_i is 0 to rounding.
//
// The joints (indices 6, 7) get 0, and so does every wheel while v1 = 0 or the mode is off.
#pragma once

#include "core/behaviour/switches.hpp"
#include "core/params.hpp"

namespace marsokhod::behaviour {

// (6.5) h^v [rad/s], scaled into [−H, H] as above; zero while v1 = 0. loads_radps holds all
// eight motors' l; the joints' entries are ignored. Throws std::invalid_argument if a wheel
// load or v1 is not finite, the gain is negative, H is not > 0, or loads far outside any
// physical range overflow the arithmetic.
MotorVector variance_load_distribution_radps(const MotorVector& loads_radps,
                                             double drive_speed_radps,
                                             const LoadDistributionParams& params);

// (6.6) h^s [rad/s], scaled into [−H, H] as above; zero while v1 = 0. Throws as (6.5).
MotorVector slip_load_distribution_radps(const MotorVector& loads_radps, double drive_speed_radps,
                                         const LoadDistributionParams& params);

// The correction of the mode switched on (switches.load_distribution): h^v, h^s, or zero.
MotorVector load_distribution_radps(const MotorVector& loads_radps, double drive_speed_radps,
                                    const LoadDistributionParams& params,
                                    const BehaviourSwitches& switches);

}  // namespace marsokhod::behaviour
