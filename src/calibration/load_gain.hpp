// Procedures 4.13 and 4.14: the functions B⁺_icr(d), B⁻_icr(d) of (4.6) as a [[load_gain]] table,
// and the check that they do not depend on the supply voltage.
//
// Procedure 4.13 strapped a weight to the front-left wheel and swept the duty; (4.7)'s constants
// are what it found at d ≥ 0.3 and low modulation frequency (`calibrate load`). Figure 4.8 drew
// the whole functions, which rise toward small duty at high frequency; Procedure 4.14 repeated the
// sweep with a lighter weight (peak ±2.98 N·m) at U = 24, 22, 20 and 16 V and found "the defect in
// velocity is not susceptible to the supply voltage". Here the wheel is held at a few duty levels
// in turn (the wheel must turn over at each to show both signs of τ), at each supply voltage
// (24, 22 and 20 V: 16 V is below the onboard computer's brown-out), and at every level
//   l = w − ν = c + B⁺·τ⁺ + B⁻·τ⁻,   τ = peak·sin(p̄ + phase),
// τ⁺ = τ where τ·d ≥ 0, τ⁻ = τ where τ·d < 0; c takes up what ν misses of the wheel's no-load speed
// at that level. The phase (where the weight sits) is one for all levels and voltages: the first
// harmonic of l with an offset per level. A voltage whose B± at a level lies further from the
// level's mean over the voltages than `max_voltage_spread` (relative) refuses the table: (4.6)
// would then need U, which the driver's model does not have.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "calibration/fit.hpp"

namespace marsokhod::calibration {

// One cycle of one voltage's run.
struct LoadGainSample {
  std::size_t level = 0;      // index into the duty levels
  double duty = 0.0;          // d sent
  double position_rad = 0.0;  // p̄ of the wheel
  double load_radps = 0.0;    // l = w − ν
};

struct LoadGainRun {
  double supply_v = 0.0;  // the laboratory supply as measured
  std::vector<LoadGainSample> samples;
};

struct LoadGainSettings {
  double peak_torque_nm = 2.98;             // Procedure 4.14's weight
  std::vector<double> duty_levels{0.2, 0.3, 0.4, 0.5, 0.6};
  double min_revolutions = 1.5;             // at each level of each run
  double max_residual_radps = 0.04;         // rms of l about the model, per run
  double max_voltage_spread = 0.10;         // relative, of B± at one level over the voltages
};

// B± at one duty level and one voltage (NaN where the level does not determine them).
struct LoadGainPoint {
  double same_sign_radps_per_nm = 0.0;
  double opposite_sign_radps_per_nm = 0.0;
  double revolutions = 0.0;
  std::size_t samples = 0;
};

struct LoadGainFit {
  double phase_rad = 0.0;
  std::vector<double> supply_v;                    // per run
  std::vector<std::vector<LoadGainPoint>> points;  // [run][level]
  std::vector<Residuals> residuals;                // per run
  // The table: B± at each level, the mean over the voltages.
  std::vector<double> duty;
  std::vector<double> same_sign_radps_per_nm;
  std::vector<double> opposite_sign_radps_per_nm;
  double max_relative_spread = 0.0;  // over levels, signs and voltages
  std::vector<std::string> problems;
};

// Never throws for bad data (problems say why); std::invalid_argument for a peak ≤ 0, no levels,
// or a sample whose level index is out of range.
LoadGainFit fit_load_gain(const std::vector<LoadGainRun>& runs, const LoadGainSettings& settings);

}  // namespace marsokhod::calibration
