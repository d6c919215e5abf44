// Summation principle (chapter 5.4): add the elementary motions and keep every motor feasible.
//
//   ŵ = Σ_j m_j v_j + n6 w6 + n7 w7                                                  (5.4)
//   |ŵ_i| ≤ ζ_i·V_icr(D)·U/Ū  for i = 0..7, V_icr(D) = W_icr(D), D ∈ (0, 1]          (5.5)
//   |m6 v6 + n6 w6 + m7 v7 + n7 w7| ≤ ζ·V_icr(D)·U/Ū                                 (5.6)
//   ŵ = κ·Σ_{j=1..4} m_j v_j + m6 v6 + n6 w6 + m7 v7 + n7 w7, κ ∈ [0, 1] the largest feasible
//
// The thesis scales j = 1..3; the trench motion m4 is a driving motion as well and is scaled with
// them here (its v4 comes from the same stick as the gait speed, so it must yield to walking).
// Per motor the constraint is |aκ + b| ≤ c with a the driving part, b the walking part, c the
// bound; with |b| ≤ c:
//   κ_i = (c − |b|)/|a| if sgn a = sgn b, (c + |b|)/|a| otherwise (b = 0 falls in either case),
//   κ = min(1, min over a_i ≠ 0 of κ_i).
// (5.6) is an assumption of the thesis; if the walking part violates it anyway, it is scaled down
// first by the largest λ ∈ [0, 1] that fits (walking_scale < 1 and walking_scaled = true report
// it), then κ is found for the scaled walking part. λ = 1 and κ = 1 whenever ŵ of (5.4) is
// already feasible, so a feasible command passes unchanged.
#pragma once

#include "core/adaptation/motor_curve.hpp"
#include "core/params.hpp"

namespace marsokhod::mobility {

// The right-hand side of (5.5) for each motor: ζ_i·W(D)·U/Ū [rad/s]. Throws
// std::invalid_argument naming the argument unless ζ_i ≥ 0, D ∈ (0, 1], U ≥ 0 and Ū > 0 are
// finite.
MotorVector motor_velocity_bounds(const MotorVector& scale, double max_duty,
                                  const adaptation::MotorCurve& curve, double supply_v,
                                  double nominal_supply_v);

// κ_i for one motor, the closed form above; +∞ when a = 0. Requires |b| ≤ c (up to rounding,
// never returns less than 0). Throws std::invalid_argument naming a non-finite argument.
double driving_scale_limit(double driving_radps, double walking_radps, double bound_radps);

struct Summation {
  MotorVector velocities_radps{};  // ŵ
  double driving_scale = 1.0;      // κ
  double walking_scale = 1.0;      // λ
  bool walking_scaled = false;     // λ < 1: the walking part alone violated (5.6)
};

// ŵ from the driving part Σ_{j=1..4} m_j v_j, the walking part m6 v6 + n6 w6 + m7 v7 + n7 w7
// and the bounds of (5.5) [rad/s]. Throws std::invalid_argument naming the motor if an input is
// not finite or a bound is negative.
Summation sum_motions(const MotorVector& driving_radps, const MotorVector& walking_radps,
                      const MotorVector& bounds_radps);

}  // namespace marsokhod::mobility
