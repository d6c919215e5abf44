// (4.4) the no-load velocity the motor has reached after the recent commands, and the load of
// Definition 4.9:
//   ν^k = Σ_j δ^j ŵ^(k−j)        l^k = w^k − ν^k
// ŵ^k = ζ W(d^k) U/Ū is the no-load velocity commanded in cycle k ((4.3)), w^k the measured
// velocity. δ comes from the table after Procedure 4.8, one row per (h, con). In both of the
// thesis' rows δ⁰ = 0: the command sent in cycle k has no effect on the velocity measured in
// cycle k, so ν^k is known before ŵ^k is chosen.
#pragma once

#include <cstddef>
#include <vector>

#include "core/params.hpp"

namespace marsokhod::adaptation {

// How far the cycle period may be from a table's h and still use its δ (the thesis measured
// 0.0157 s; the driver's nominal period is 0.0156 s).
inline constexpr double kResponsePeriodTolerance_s = 0.001;

// The δ table for (period_s, con): con equal and |period_s − h| ≤ 0.001 s (the nearest h if
// several fit). Throws std::invalid_argument listing the available (h, con) pairs otherwise.
const ResponseParams& select_response(const std::vector<ResponseParams>& responses, double period_s,
                                      int con);

// ν of (4.4) for all eight motors, keeping the last N − 1 commands (N = δ's length) in a ring
// buffer.
class NoLoadEstimator {
 public:
  // History ŵ^(k−1) … ŵ^(k−N+1) all set to initial_w_hat_radps (zero: the rover stands still).
  // Throws std::invalid_argument if delta is empty or any δ or initial value is not finite.
  explicit NoLoadEstimator(const ResponseParams& response,
                           const MotorVector& initial_w_hat_radps = {});

  // ν^k with ŵ^k = w_hat_radps (weighed by δ⁰) and the recorded history. Throws on a
  // non-finite entry.
  MotorVector no_load_velocity_radps(const MotorVector& w_hat_radps) const;

  // ν^k from the history alone, for a table with δ⁰ = 0 (both of the thesis' tables). Throws
  // std::logic_error if δ⁰ ≠ 0: then ν^k needs this cycle's command.
  MotorVector no_load_velocity_radps() const;

  // Records ŵ^k: the cycle ends, k → k + 1. Throws on a non-finite entry, leaving the history
  // unchanged.
  void push(const MotorVector& w_hat_radps);

  const std::vector<double>& delta() const { return delta_; }

 private:
  // Σ_(j ≥ 1) δ^j ŵ^(k−j).
  MotorVector history_sum_radps() const;

  std::vector<double> delta_;
  std::vector<MotorVector> history_;  // ring buffer of ŵ, history_[newest_] = ŵ^(k−1)
  std::size_t newest_ = 0;
};

// Definition 4.9: l = w − ν in rad/s. Throws std::invalid_argument on a non-finite argument.
double load(double measured_velocity_radps, double no_load_velocity_radps);
MotorVector load(const MotorVector& measured_velocity_radps,
                 const MotorVector& no_load_velocity_radps);

}  // namespace marsokhod::adaptation
