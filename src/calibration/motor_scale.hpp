// Procedure 4.5: the scale factor ζ_i of each wheel from a long run at d = 0.7 on the stand:
//   ζ_i := mean_k (Ū/U^k)·(w_i^k / W_icr(0.7))
// with W the configured curve (after a Procedure 4.4 calibration, the mean of the wheels' curves,
// so that the ζ_i are relative to it). The first seconds (the wheels speeding up) are left out.
// The joints cannot turn freely: ζ6 := ζ1 and ζ7 := ζ4 by the shared power cables (thesis).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/params.hpp"

namespace marsokhod::calibration {

struct MotorScaleSample {
  double time_s = 0.0;
  double supply_v = 0.0;                           // U^k
  std::array<double, kWheelCount> velocity_radps{};  // w_i^k of the six wheels
};

struct MotorScaleFitSettings {
  double nominal_supply_v = 24.0;   // Ū
  double curve_speed_radps = 2.10;  // W_icr(d) at the duty held
  double settle_s = 3.0;            // left out at the start (speeding up)
  double min_duration_s = 20.0;     // of the samples kept
  double max_relative_scatter = 0.01;  // σ of the per-sample ratio, relative to ζ_i
  double max_supply_deviation_v = 2.0;
};

struct MotorScaleFit {
  MotorVector scale{};                                    // ζ_0 … ζ_7 (ζ6 = ζ1, ζ7 = ζ4)
  std::array<double, kWheelCount> relative_scatter{};     // σ_k of the ratio / ζ_i
  std::array<double, kWheelCount> drift_per_min{};        // slope of the ratio / ζ_i [1/min]
  double duration_s = 0.0;                                // of the samples used
  std::size_t samples = 0;
  double mean_supply_v = 0.0;
  std::vector<std::string> problems;
};

// Never throws for bad data (problems say why); std::invalid_argument for a non-positive W or Ū.
MotorScaleFit fit_motor_scale(const std::vector<MotorScaleSample>& samples,
                              const MotorScaleFitSettings& settings);

}  // namespace marsokhod::calibration
