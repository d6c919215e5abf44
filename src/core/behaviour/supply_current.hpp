// Field Experiment 1.1: on the tether the laboratory supply (24 V, 6 A: Figure 4.2's PS 613)
// holds its voltage only up to its current limit; above it the voltage folds back, and about 1 A
// further it falls below the onboard computer's 19.5 V: the rover browns out. (6.3) cannot prevent
// that — it bounds the voltage drop of the batteries' linear model (4.5), and the tether's drop
// stays a few tenths of a volt right up to the limit, then collapses within a cycle when a wheel
// strikes a stone or a joint starts to lift the chassis. So on the tether the driver bounds the
// current the duty cycles could draw whatever the loads do: the current if every motor stalled.
//
// One motor at duty d, shaft speed w and supply U (every quantity at the output shaft):
//   x = max(0, |d|·U − U_dz)                  the voltage that turns the motor
//   τ_s = max(τ_hold, c·x)                     the most torque it can give (its stall torque)
//   τ_s += |w|/B⁻, at most c·(U − U_dz)        if w turns against d (plugging, below)
//   I = I0 + I1·|w| + |d|·τ_s/k_t   (d ≠ 0),   I = 0   (d = 0: the bridge does not switch)
// The motor's current τ/k_t flows from the supply only while the bridge conducts, a share |d| of
// each PWM period (the bridge is a buck converter: U·I_supply = |d|·U·I_motor), and no load can
// make τ exceed τ_s; so I bounds what the motor draws, whatever it meets. A shaft that turns
// against its duty (a wheel still spinning the old way as a spin reverses, or dragged back) adds
// its back-EMF to the bridge's voltage: its torque along d grows past the stall torque by |w|/B⁻
// of (4.7), up to the full-duty stall torque, and its current is drawn from the supply like a
// motoring one's. w is the last measured speed (w̄, a cycle old); a plugging shaft slows. The
// rover's bound is the stationary rover's I_base (chapter 3.1) plus the eight motors'. U is the
// highest supply µ8's reading admits (the driver's caller, motion_controller.cpp): max(U, Ū) plus
// `supply_reading_error_v`, the conversion's error before Procedure 3.5 (1.2 V: the divider's
// ±1.5 % over the conversion's 65 V span and 3 counts). Without it a unit reading U 0.9 V low
// drew up to 6.22 A at a spin's reversal (units 171 and 195 of 1–400).
//
// The duty bound: D_I, the largest D of (5.5) whose duties — the motions of (5.4) scaled under D,
// the load distribution, (4.3)'s inverse, then chapter 3.2's slew rule from the duties sent last —
// keep the bound within the tether's limit; D = min(D of (6.3), D_I). The bound mostly grows with
// D (not always: below), so bisection finds D_I; acting through (5.5) it scales every motion
// alike (κ), so the wheels and the joints keep the kinematics of (5.4) — lowering some duties
// alone would set wheels against each other, which draws more current, not less. Six wheels at
// one duty d on 24 V, the joints still: 6·(0.12 + d·1.74·(24d − 1)/7.5) + 1.05 ≤ 6 A gives
// d ≤ 0.377 (the shipped constants): on the tether the rover drives at about 0.38 of full speed,
// as the tether allows.
#pragma once

#include <cmath>

#include "core/params.hpp"

namespace marsokhod::behaviour {

// I of one motor [A] at duty d, shaft speed w [rad/s] and supply U [V]. Throws
// std::invalid_argument for a duty outside [−1, 1], a speed that is not finite or a supply
// voltage that is not finite and ≥ 0.
double motor_current_bound_a(double duty, double shaft_velocity_radps, double supply_v,
                             const SupplyCurrentParams& params);

// The resolution of D_I: a step of D moves no duty by more than the step (κ ≤ 1), and 1/1024 is
// about one pwm count at the largest icr (1/1023), half of one at the shipped icr = 511. So a
// finer D_I could not change what the controllers apply by more than a count: ten halvings of
// [0.05, 1] instead of twenty (the tether's cycle costs 0.38 µs an evaluation, BENCHMARKS.md).
inline constexpr double kDutyBoundResolution = 1.0 / 1024.0;

// The largest D in [low, high] whose bound `current_at(D)` [A] is within `limit_a`, to within
// kDutyBoundResolution below it, by bisection; `low` when even it is over. `current_at` is any
// callable double(double); where it is not non-decreasing, the answer is an admitted D whose next
// halving step is over the limit.
template <class CurrentAt>
double current_duty_bound(double low, double high, double limit_a, CurrentAt&& current_at) {
  if (current_at(high) <= limit_a) return high;
  if (current_at(low) > limit_a) return low;
  while (high - low > kDutyBoundResolution) {
    const double mid = 0.5 * (low + high);
    if (current_at(mid) <= limit_a) {
      low = mid;
    } else {
      high = mid;
    }
  }
  return low;
}

// The cell of the bisection's last halving that holds x (clamped to [low, high]): the path's
// halvings taken toward x with the bisection's own arithmetic, so that its ends are the very
// doubles the bisection compares. Every end is a point of the path; low and high are too.
struct DutyBoundCell {
  double low, high;
};
inline DutyBoundCell duty_bound_cell(double low, double high, double x) {
  DutyBoundCell cell{low, high};
  while (cell.high - cell.low > kDutyBoundResolution) {
    const double mid = 0.5 * (cell.low + cell.high);
    if (mid <= x) {
      cell.low = mid;
    } else {
      cell.high = mid;
    }
  }
  return cell;
}

// The gallop's doublings before it jumps to the bracket's end: 1, 2, 4, 8 and 16 cells.
inline constexpr int kDutyBoundGallops = 5;

// The same search started from a guess (the last cycle's D_I): it looks at the cell that holds
// the guess, gallops up or down over the cells (1, 2, 4, 8, 16, then the bracket's end) to an
// admitted D below one over the limit, then halves between them, always on the bisection's own
// cell ends. Two evaluations of the bound when D_I stays in its cell, a few when it moved a few
// cells, at most 19 (a jump across the bracket) against the bisection's fixed 12; one when the
// guess lies in the last cell and the bound does not bind. A cell whose lower end is admitted and
// upper end is not is the answer. Where the bound is non-decreasing there is only one such cell,
// the one the bisection ends in, so the answer is the bisection's own double. The real bound is a
// staircase of pwm counts, and it can dip as D grows: by 0.3 A on `tether-current-bound`, seed 3,
// at D ≈ 0.51–0.55, where the rear wheels' summed motion (driving and rolking's strokes, which
// (5.5) scales differently) passes through zero — their duties go from −1 count to 0, and a bridge
// at d = 0 draws nothing. There the two may stop in different cells, each an admitted D whose next
// cell end is over the limit, and the warm start's answer depends on where it started. A bracket
// that is not finite and ordered goes to the plain bisection.
template <class CurrentAt>
double current_duty_bound_from(double guess, double low, double high, double limit_a,
                               CurrentAt&& current_at) {
  if (!(std::isfinite(low) && std::isfinite(high) && low <= high)) {
    return current_duty_bound(low, high, limit_a, current_at);
  }
  const auto admitted = [&](double duty) { return current_at(duty) <= limit_a; };
  int high_known = -1;  // the verdict on `high`, asked at most once: -1 not yet, 0 over, 1 admitted
  const auto high_admitted = [&] {
    if (high_known < 0) high_known = admitted(high) ? 1 : 0;
    return high_known == 1;
  };
  const auto cell_at = [&](double x) { return duty_bound_cell(low, high, x); };
  const DutyBoundCell start = cell_at(guess);
  const double step = start.high - start.low;
  // In the last cell the answer may be `high` itself: ask it first.
  if (start.high >= high && high_admitted()) return high;
  double ok = low, over = high;  // an admitted cell end below one over the limit
  if (admitted(start.low)) {
    ok = start.low;
    over = start.high;  // 1 cell above
    for (int gallop = 1;; ++gallop) {
      if (over >= high) {
        if (high_admitted()) return high;
        break;
      }
      if (!admitted(over)) break;
      ok = over;
      over = gallop == kDutyBoundGallops ? high
                                         : cell_at(ok + ((1 << gallop) - 0.5) * step).high;
    }
  } else {
    if (start.low <= low) return low;
    over = start.low;
    for (int gallop = 0;; ++gallop) {
      const double below = gallop == kDutyBoundGallops
                               ? low
                               : cell_at(over - ((1 << gallop) - 0.5) * step).low;
      if (admitted(below)) {
        ok = below;
        break;
      }
      if (below <= low) return low;
      over = below;
    }
  }
  // Halve the cells between ok and over until they are neighbours (about log2 of their number, at
  // most 11 for the bracket's 2^10 cells; the cap only guards against arithmetic not foreseen).
  for (int halving = 0; halving < 64; ++halving) {
    const DutyBoundCell middle = cell_at(0.5 * (ok + over));
    const double probe = middle.low > ok ? middle.low : middle.high;
    if (probe >= over) return ok;
    if (admitted(probe)) {
      ok = probe;
    } else {
      over = probe;
    }
  }
  return ok;
}

}  // namespace marsokhod::behaviour
