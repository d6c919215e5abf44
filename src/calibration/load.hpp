// Procedure 4.13: B⁺ and B⁻ of (4.6)/(4.7) from a weight strapped to the front-left wheel on the
// stand. The weight's gravity torque on the free wheel is periodic in the wheel's angle,
// τ(α) = peak·sin α (α = 0 with the weight at the top); the duty rises sedately over [0, 0.6] and
// the load l = w − ν (ν of (4.4) with the configured δ, ζ, W) is recorded against the shaft
// position p̄. The fit, over the duties where (4.7)'s constants hold (d ≥ 0.3: Figure 4.8's rise at
// small duty and high PWM frequency is over), is in two steps:
//   1. the phase: l ≈ c0 + c1·d + c2·d² + a·sin p̄ + b·cos p̄ gives α = p̄ + atan2(b, a) (the strap's
//      spot is unknown to the software; B > 0 makes l follow τ in sign);
//   2. l ≈ c0 + c1·d + c2·d² + B⁺·τ⁺ + B⁻·τ⁻ with τ⁺ = τ where τ·d ≥ 0, τ⁻ = τ where τ·d < 0.
// The polynomial in d takes up what the configured ζ·W misses of this wheel's no-load speed (a
// slow function of d); the weight's torque changes once per revolution.
#pragma once

#include <string>
#include <vector>

#include "calibration/fit.hpp"

namespace marsokhod::calibration {

struct LoadSample {
  double time_s = 0.0;
  double duty = 0.0;        // d sent
  double position_rad = 0.0;  // p̄ of the wheel
  double load_radps = 0.0;    // l = w − ν
};

struct LoadFitSettings {
  double peak_torque_nm = 5.51;  // the weight's (Procedure 4.13)
  double min_duty = 0.3;
  double max_duty = 0.6;
  double min_revolutions = 3.0;     // within [min_duty, max_duty]
  double max_residual_radps = 0.04;  // rms of l about the model
  // The weight must show: the periodic part of l at least this many times the residual.
  double min_signal_to_noise = 3.0;
  std::vector<double> bin_edges{0.3, 0.4, 0.5, 0.6};  // B±(d) per duty bin (Figure 4.8)
};

struct LoadFit {
  double same_sign_radps_per_nm = 0.0;      // B⁺
  double opposite_sign_radps_per_nm = 0.0;  // B⁻
  double phase_rad = 0.0;                   // α = p̄ + phase
  double amplitude_radps = 0.0;             // of the first harmonic of l
  double revolutions = 0.0;
  Residuals residuals;
  std::size_t samples = 0;
  std::vector<double> bin_duty;             // centres
  std::vector<double> bin_same_sign;        // B⁺ per bin (NaN where undetermined)
  std::vector<double> bin_opposite_sign;
  std::vector<std::string> problems;
};

// Never throws for bad data (problems say why); std::invalid_argument for a peak ≤ 0.
LoadFit fit_load(const std::vector<LoadSample>& samples, const LoadFitSettings& settings);

}  // namespace marsokhod::calibration
