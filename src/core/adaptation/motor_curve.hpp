// W_icr(d), the no-load velocity of a Maxon RE 36 at the nominal supply Ū against the duty cycle
// d (Procedure 4.4), and its inverse W⁻¹ (used by (4.3) and Remark 4.7).
//   W is the piecewise-linear interpolation of a calibration table (d_i, W_i), i = 0..n−1, with
//   0 = d_0 < d_1 < … < d_(n−1) = 1 and 0 = W_0 < W_1 < … < W_(n−1) = w_max;
//   W(−d) = −W(d); |d| > 1 saturates to ±w_max.
//   W⁻¹ interpolates the same nodes with the axes swapped, so W⁻¹(W(d)) = d up to rounding and
//   exactly at the nodes; W⁻¹(−v) = −W⁻¹(v); |v| > w_max saturates to ±1.
// Both are monotone non-decreasing in floating point as well (each result is clamped to its
// segment).
#pragma once

#include <vector>

#include "core/params.hpp"

namespace marsokhod::adaptation {

class MotorCurve {
 public:
  // Validates the table: duty and no_load_speed_radps of equal length ≥ 2, duty strictly
  // increasing from exactly 0 to exactly 1, speeds finite and strictly increasing from exactly 0.
  // Throws std::invalid_argument naming the field and the index.
  explicit MotorCurve(const MotorCurveParams& params);

  int icr() const { return icr_; }
  double max_velocity_radps() const { return velocity_radps_.back(); }  // w_max = W(1)

  // W(d) in rad/s. Throws std::invalid_argument if duty is not finite; |duty| > 1 saturates.
  double velocity_radps(double duty) const;

  // W⁻¹(v), a duty cycle in [−1, 1]. Throws if velocity_radps is not finite; |v| > W(1)
  // saturates to ±1.
  double duty(double velocity_radps) const;

 private:
  int icr_;
  std::vector<double> duty_;
  std::vector<double> velocity_radps_;
};

// The table for one icr out of Params::motor_curves. Throws std::invalid_argument listing the
// available icr values when none matches.
const MotorCurveParams& select_motor_curve(const std::vector<MotorCurveParams>& curves, int icr);

}  // namespace marsokhod::adaptation
