// Procedure 4.4: W_icr(d), the no-load speed at the nominal supply Ū against the duty cycle, from
// a slow sweep of pwm on the stand (wheels free):
//   W_icr(pwm/icr) := w·Ū/U
// The sweep goes up from d = 0 to 1, holds d = 1 for a moment and comes back down. At each duty
// of the grid (0, 0.1, …, 1) a line through the samples within ±window of it gives the value on
// the way up and on the way down; their mean cancels the delay of the measured speed behind the
// duty (≈ 40 ms: the motor's lag, the shaft's inertia, µi's velocity window) to first order, and
// their difference (the hysteresis) says whether the sweep was sedate enough.
//
// ζ and W: every measured wheel i gives its own curve W_i(d) = ζ_i·W(d) (the wheel's bearing
// friction scales it, Procedure 4.5). W is the mean over the measured wheels, so a later
// Procedure 4.5 finds ζ_i relative to it (their mean ≈ 1) and ζ_i·W(d) is each wheel's own curve.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/params.hpp"

namespace marsokhod::calibration {

enum class SweepPhase { kRising, kTop, kFalling };

struct MotorCurveSample {
  double time_s = 0.0;
  double duty = 0.0;                   // the duty sent (≥ 0; drv = 0)
  double supply_v = 0.0;               // U measured this cycle
  std::vector<double> velocity_radps;  // w̄ of each measured wheel, in the order of `wheels`
  SweepPhase phase = SweepPhase::kRising;
};

struct MotorCurveFitSettings {
  int icr = 511;
  double nominal_supply_v = 24.0;  // Ū
  std::vector<double> duty_grid{0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
  double window_duty = 0.02;          // half-width of the local line fits
  std::size_t min_window_samples = 20;  // per grid duty and direction
  // Refusals: up and down sweeps that disagree (too fast), scatter about the local lines
  // (noise), a supply too far from Ū for the normalisation by Ū/U to hold.
  double max_hysteresis_radps = 0.03;
  double max_residual_radps = 0.03;
  double max_supply_deviation_v = 2.0;
  // Below this a grid value counts as inside the dead zone (see MotorCurveFit::notes).
  double dead_zone_speed_radps = 0.01;
};

struct MotorCurveFit {
  MotorCurveParams curve;  // icr, duty grid, W at the grid (W(0) = 0)
  // Per measured wheel: W_i at the grid (the mean of the way up and the way down).
  std::vector<std::vector<double>> wheel_speed_radps;
  std::vector<double> rising_radps;   // W on the way up, at the grid (mean over wheels)
  std::vector<double> falling_radps;  // on the way down
  double max_hysteresis_radps = 0.0;  // max over grid and wheels of |up − down|
  double rms_residual_radps = 0.0;    // scatter of the samples about the local lines
  double max_wheel_spread = 0.0;      // max over grid (d ≥ 0.3) of |W_i/W − 1|
  double mean_supply_v = 0.0;
  std::size_t samples = 0;
  std::vector<std::string> problems;  // non-empty: refuse
  std::vector<std::string> notes;
};

// Fits W from the samples of a sweep; never throws for bad data (problems say why), throws
// std::invalid_argument only for inconsistent arguments (velocity vectors of unequal length, a
// grid that does not run strictly increasing from 0 to 1).
MotorCurveFit fit_motor_curve(const std::vector<MotorCurveSample>& samples,
                              const MotorCurveFitSettings& settings);

}  // namespace marsokhod::calibration
