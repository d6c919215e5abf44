// Procedure 3.5: the affine relation U = gain·vcc + offset of µ8's supply reading, from readings
// at several supply voltages (27 down to 20 V, battery operation's range).
#pragma once

#include <vector>

#include "calibration/procedure.hpp"

namespace marsokhod::calibration {

// One supply voltage of the procedure.
struct VoltagePoint {
  double measured_v = 0.0;       // U by the multimeter at the power distribution board
  double vcc_mean_counts = 0.0;  // µ8's ADC6 reading, averaged over the hold
  double vcc_sd_counts = 0.0;    // its spread over the hold
  std::size_t samples = 0;
};

// Acceptance limits of the fit (docs/calibration.md).
struct VoltageFitLimits {
  std::size_t min_points = 4;
  std::size_t min_samples_per_point = 32;
  double min_span_v = 3.0;         // the voltages must spread at least this much
  double max_point_sd_counts = 2.0;  // a steady supply reads within quantisation and noise
  // The thesis: 10-bit quantisation keeps the error below ±34 mV; allow noise on top.
  double max_residual_v = 0.08;
};

// Fits U = gain·vcc + offset; the result's problems say why a fit must not be written.
ProcedureResult fit_voltage(const std::vector<VoltagePoint>& points,
                            const VoltageFitLimits& limits = {});

}  // namespace marsokhod::calibration
