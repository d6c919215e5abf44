// (4.6), (4.7) the load l = w − ν caused by an external torque τ on the motor, in the
// simplification the thesis justifies at icr = 511 and lower modulation frequencies:
//   l = τ · B⁺  if τ d ≥ 0   (the torque pushes along the drive direction, or d = 0)
//   l = τ · B⁻  if τ d < 0   (the torque opposes it)
// with B⁺ = 0.030, B⁻ = 0.015 rad/(s N m) (LoadParams). Since B± > 0, sgn τ = sgn l, so the
// inverse picks B⁺ when l d ≥ 0 and τ = l/B±; the round trip is exact up to rounding.
//
// (4.6) in full, l = τ·B^(sgn τd)_icr(d): B⁺ and B⁻ are functions of the duty cycle, one pair per
// icr (LoadGainParams, Procedure 4.13, Figure 4.8). gains_at() evaluates the table at d — linear
// in |d| between its entries, constant beyond its ends, even in d — and the two functions below
// then apply (4.6) at that d exactly as (4.7).
#pragma once

#include <vector>

#include "core/params.hpp"

namespace marsokhod::adaptation {

// l in rad/s. Throws std::invalid_argument if torque_nm is not finite, duty is not finite or
// outside [−1, 1], or B⁺, B⁻ is not finite and positive.
double load_from_torque(double torque_nm, double duty, const LoadParams& load);

// τ in N m. Same checks with load_radps in place of torque_nm.
double torque_from_load(double load_radps, double duty, const LoadParams& load);

// B⁺_icr(d), B⁻_icr(d) of (4.6) from one table. Throws std::invalid_argument if duty is not finite
// or outside [−1, 1], or the table is empty or its columns differ in length.
LoadParams gains_at(const LoadGainParams& table, double duty);

// The table for one icr out of Params::load_gains. Throws std::invalid_argument listing the
// available icr values when none matches.
const LoadGainParams& select_load_gains(const std::vector<LoadGainParams>& tables, int icr);

// (4.6): τ [N m] from the load l [rad/s] at duty d with B±(d) of `table`. NaN for a load that is
// not finite (a motor not yet tracked); otherwise the checks of torque_from_load and gains_at.
double torque_estimate_nm(double load_radps, double duty, const LoadGainParams& table);

}  // namespace marsokhod::adaptation
