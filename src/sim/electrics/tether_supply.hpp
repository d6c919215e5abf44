// The 0–30 V laboratory supply on a tether (Figure 4.2: the PS 613), for indoor driving.
//
//   U = U_set − I·R_cable                                 I ≤ I_limit (constant voltage)
//   U = U_set − I·R_cable − k_fold·(I − I_limit)          I > I_limit (foldback)
// clamped at 0. The loads are currents, so the supply cannot hold I at the limit by itself; the
// steep foldback lowers U, the motors' no-load speeds fall with it and their current follows:
// the regulation closes through the motor model and the physics, as it does on the real rover.
#pragma once

#include "sim/electrics/sim_truth.hpp"

namespace marsokhod::sim {

class TetherSupply {
 public:
  // Throws std::invalid_argument unless set_v ∈ [0, 30] V, the limit > 0 and resistances ≥ 0.
  explicit TetherSupply(const TetherTruth& truth);

  // The supply has no memory; dt_s is accepted for symmetry with Battery.
  double step(double current_a, double dt_s) const;
  double terminal_voltage_v(double current_a) const;

  bool current_limited(double current_a) const { return current_a > truth_.current_limit_a; }
  // The knob on the laboratory supply (Procedure 3.5 turns it from 27 down to 20 V); throws
  // std::invalid_argument outside 0..30 V.
  void set_voltage(double set_v);
  double set_voltage_v() const { return truth_.set_v; }
  // The sag fault: an extra resistance in the tether (a long or damaged cable).
  void set_extra_resistance_ohm(double resistance_ohm);

 private:
  TetherTruth truth_;
  double extra_resistance_ohm_ = 0.0;
};

}  // namespace marsokhod::sim
