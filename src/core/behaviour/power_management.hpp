// Chapter 6.1 power management: the bound D on the duty cycles, max_i |d_i| ≤ D of (5.5), that
// keeps the supply voltage drop (4.5) Ū − U = ξ Σ_i |d_i| + Ξ Σ_i l_i² under Υ.
//
//   D(L) = (Υ − Ξ L) / (n ξ)                                                         (6.1)
//     with n motors all at |d| = D and L = Σ_i l_i². The thesis prints n = 8; Example 6.1's
//     numbers (D(0) = 0.417 …) come out with n = 6 and Ξ = 0.3 (docs/design.md), so n is an argument.
//
//   D^(k+1) = min( max_i |d_i^k| / Σ_i |d_i^k| · (Υ − Ξ Σ_i (l_i^k)²) / ξ , 1 )          (6.3)
//     if d_i^k ≠ 0 for some motor i, otherwise D^(k+1) = 1. The factor max/Σ replaces 1/8 of
//     (6.1): it is 1/8 when all eight |d_i| are equal, 1 when one motor runs alone.
//
// The floor: when the measured loads alone spend the budget (Ξ Σ l² ≥ Υ, e.g. every wheel
// stalled at |l| ≥ 0.68 rad/s), (6.3) turns zero or negative. A negative D is meaningless (it
// would flip the signs of the scaled motions of (5.5)), and D = 0 freezes the rover: the duty
// falls to 0, the next cycle sees d = 0 and returns D = 1, and the rover lurches between a
// stop and full power. We clamp D^(k+1) to [kMinimumDutyBound, 1] instead. At D = 0.05 the duty
// term costs at most 8 · 0.6 V · 0.05 = 0.24 V, and since the no-load velocity ν follows the
// duty, lowering d shrinks |l| = |w − ν| of stalled wheels, so D recovers within a few cycles
// without the rover ever stopping dead. Stopping is left to the operator and the safety layer
// (dead man's switch, operator timeout), which know why the rover should stand still.
#pragma once

#include <cstddef>

#include "core/behaviour/switches.hpp"
#include "core/params.hpp"

namespace marsokhod::behaviour {

// The least D that (6.3) returns: one duty step (SafetyParams::max_duty_step = 0.05), so a
// rate-limited duty can still follow it from rest in one cycle.
inline constexpr double kMinimumDutyBound = 0.05;

// (6.1), as printed and unclamped (negative when Ξ L > Υ): the duty D that n motors running at
// |d| = D may share under the load-square sum L [rad²/s²]. Throws std::invalid_argument if L
// is negative or not finite, motor_count is 0, ξ is not > 0, or Ξ, Υ are negative.
double equal_duty_bound(double load_square_sum_rad2_per_s2, std::size_t motor_count,
                        const PowerParams& power);

// (6.3) with the floor above: D^(k+1) in [kMinimumDutyBound, 1] from this cycle's duties d^k
// and loads l^k [rad/s] of all eight motors; 1 when power management is switched off. The
// budget Υ − Ξ Σ l² is reduced further by `unmodelled_drop_v` ≥ 0, the part of the measured
// drop that (4.5) does not predict (MeasuredDropExcess). Throws std::invalid_argument for a duty
// outside [−1, 1], a non-finite load, a negative or non-finite unmodelled drop, or bad
// PowerParams.
double next_duty_bound(const MotorVector& duties, const MotorVector& loads_radps,
                       const PowerParams& power, const BehaviourSwitches& switches,
                       double unmodelled_drop_v = 0.0);

// Feedback from the measured drop: (6.3) steers by the model (4.5), ξ Σ|d| + Ξ Σ l², and the
// model can be low — in a spin on the spot the wheels' skid loads draw more current than Ξ Σ l²
// says (seen in the simulator: 1.54–1.67 V measured for ten cycles where (4.5) gave 1.50 V),
// and a battery sagging under a fault or the cold has a higher internal resistance than ξ, Ξ
// were fitted on. Each cycle the excess of the measured drop over the modelled one,
//   ε^k = max(0, (Ū − U)^k − (ξ Σ|d^(k−1)| + Ξ Σ (l^k)²)),
// is taken at once when it grows and released with the time constant kDropExcessReleaseS when
// it shrinks, and (6.3) budgets for it. Where the model is high (the usual case: the duty term
// over-predicts a free-rolling rover), ε = 0 and (6.3) is the thesis' own.
inline constexpr double kDropExcessReleaseS = 0.5;

class MeasuredDropExcess {
 public:
  // Feeds this cycle's measured drop Ū − U and the model's drop [V] over period_s [s]; returns
  // the excess to budget for. Throws std::invalid_argument for a non-finite drop or a period
  // that is not > 0; the state is unchanged then.
  double update(double measured_drop_v, double modelled_drop_v, double period_s);
  double excess_v() const { return excess_v_; }
  void reset() { excess_v_ = 0.0; }

 private:
  double excess_v_ = 0.0;
};


}  // namespace marsokhod::behaviour
