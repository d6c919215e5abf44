// (4.5) the supply voltage drop under duty and load (Field Experiment 4.11):
//   Ū − U = ξ Σ_i |d_i| + Ξ Σ_i l_i²
// ξ [V] and Ξ [V s²/rad²] fit the rover's two battery pairs (PowerParams: 0.6 V, 0.4 V s²/rad²).
// The sums run over the entries given: the eight motors of (4.5), or the six wheels of
// Remark 4.12.
#pragma once

#include <span>

#include "core/params.hpp"

namespace marsokhod::adaptation {

// Ū − U in volts. Throws std::invalid_argument if the spans differ in length, a duty is not
// finite or outside [−1, 1], a load is not finite, or ξ, Ξ is negative or not finite.
double voltage_drop_v(std::span<const double> duties, std::span<const double> loads_radps,
                      const PowerParams& power);

}  // namespace marsokhod::adaptation
