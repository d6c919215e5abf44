// (4.6), (4.7) the load l = w − ν caused by an external torque τ on the motor, in the
// simplification the thesis justifies at icr = 511 and lower modulation frequencies:
//   l = τ · B⁺  if τ d ≥ 0   (the torque pushes along the drive direction, or d = 0)
//   l = τ · B⁻  if τ d < 0   (the torque opposes it)
// with B⁺ = 0.030, B⁻ = 0.015 rad/(s N m) (LoadParams). Since B± > 0, sgn τ = sgn l, so the
// inverse picks B⁺ when l d ≥ 0 and τ = l/B±; the round trip is exact up to rounding.
#pragma once

#include "core/params.hpp"

namespace marsokhod::adaptation {

// l in rad/s. Throws std::invalid_argument if torque_nm is not finite, duty is not finite or
// outside [−1, 1], or B⁺, B⁻ is not finite and positive.
double load_from_torque(double torque_nm, double duty, const LoadParams& load);

// τ in N m. Same checks with load_radps in place of torque_nm.
double torque_from_load(double load_radps, double duty, const LoadParams& load);

}  // namespace marsokhod::adaptation
