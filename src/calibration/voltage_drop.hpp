// (4.5) from a recorded drive (Field Experiment 4.11, Figure 4.6):
//   Ū − U = ξ·Σ_i |d_i| + Ξ·Σ_i l_i²        i = 0 … 7, no intercept
// ξ [V] and Ξ [V s²/rad²] by least squares over the cycles of a recording: the driver's duty
// cycles d_i, its loads l_i (4.4), the measured supply voltage U and the reference Ū (Procedure
// 3.5), as `marsokhod scenario --out DIR` (or `run --record`) writes them to telemetry.csv.
#pragma once

#include <filesystem>
#include <vector>

#include "calibration/fit.hpp"
#include "calibration/procedure.hpp"
#include "core/params.hpp"

namespace marsokhod::calibration {

// One control cycle of the recording.
struct VoltageDropSample {
  double time_s = 0.0;
  MotorVector duty{};        // d_i as sent
  MotorVector load_radps{};  // l_i
  double supply_v = 0.0;            // U
  double reference_supply_v = 0.0;  // Ū
};

// What the data must show before (4.5) is fitted to it.
inline constexpr std::size_t kVoltageDropMinSamples = 200;
// Duty cycles, loads and the drop are averaged over the trailing second before fitting: l is a
// difference of two noisy speeds, so l² of single cycles is inflated by the tracking's
// quantisation noise (which would bias Ξ low), and a battery's polarisation follows the current
// with a lag of seconds. The drop the power management (6.3) must bound is the sustained one.
inline constexpr double kVoltageDropAveraging_s = 1.0;
// Both regressors must vary (σ over the recording) at least this much, else the recording did not
// excite that term: a run at constant duty on smooth ground cannot tell ξ from Ξ.
inline constexpr double kVoltageDropMinDutySpread = 0.3;            // σ(Σ|d|)
inline constexpr double kVoltageDropMinLoadSpread_rad2_per_s2 = 0.02;  // σ(Σl²)
// |correlation| of Σ|d| and Σl² above this: the two terms are (nearly) collinear.
inline constexpr double kVoltageDropMaxCorrelation = 0.95;
// The fit must explain this fraction of the drop's variance (R² about the mean).
inline constexpr double kVoltageDropMinRSquared = 0.6;

// Reads the cycles of a telemetry.csv in which the driver ran with a measured supply voltage
// (rows before µ8 answered, or while the onboard computer was off, are skipped). Throws
// std::runtime_error naming the file and what is missing.
std::vector<VoltageDropSample> read_voltage_drop_samples(
    const std::filesystem::path& telemetry_csv);

// The least-squares ξ, Ξ of (4.5) (on the averaged cycles) with its residuals; `problems` when
// the data is too short, does not excite both terms, gives a negative coefficient, or is
// explained poorly.
ProcedureResult fit_voltage_drop(const std::vector<VoltageDropSample>& samples);

// How well (4.5) with these ξ, Ξ predicts the (averaged) drop of a recording [V]: to judge a fit
// on a drive it was not fitted to.
Residuals voltage_drop_prediction_residuals(const std::vector<VoltageDropSample>& samples,
                                            double duty_drop_v, double load_drop_v_s2_per_rad2);

}  // namespace marsokhod::calibration
