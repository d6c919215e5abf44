// Two 12 V lead-acid blocks in series (2 × HYS1250 or 2 × HYS1240), the rover's field supply.
//
//   OCV(s) = blocks·(empty_block_v + block_v_per_charge·s)     [V]   s = state of charge 0..1
//   R(s)   = r_full + r_empty_extra·(1 − s)² + r_extra           [Ω]   r_extra: the sag fault
//   τ_p·dV_p/dt = I·R_p − V_p                                    polarisation
//   U = OCV(s) − I·R(s) − V_p                                    terminal voltage
//   ds/dt = −I/(3600·capacity_ah)
// With the defaults a full pair rests at 25.5 V and an empty one at 23.6 V; R rises from 0.15 to
// 0.30 Ω. A current step sags U by I·R at once and by I·R_p more over τ_p = 5 s, and U recovers
// the same way when the load stops: the "voltage drop … proportional to the power consumption"
// of Figure 3.6 that the driver's (4.5) approximates.
#pragma once

#include "sim/electrics/sim_truth.hpp"

namespace marsokhod::sim {

class Battery {
 public:
  // Throws std::invalid_argument for a non-positive capacity, block count, time constant, or a
  // negative resistance, naming the field.
  explicit Battery(const BatteryTruth& truth);

  // Draws current_a for dt_s (exact for a current held over the step); returns U after it.
  double step(double current_a, double dt_s);

  // U if current_a were drawn now, without advancing time.
  double terminal_voltage_v(double current_a) const;
  double open_circuit_voltage_v() const;
  double internal_resistance_ohm() const;
  double state_of_charge() const { return state_of_charge_; }
  double polarisation_v() const { return polarisation_v_; }

  // Faults: a corroded connector or tired cell (extra series resistance), a half-empty battery.
  void set_extra_resistance_ohm(double resistance_ohm);
  void set_state_of_charge(double state_of_charge);

 private:
  BatteryTruth truth_;
  double state_of_charge_;
  double polarisation_v_ = 0.0;
  double extra_resistance_ohm_ = 0.0;
};

}  // namespace marsokhod::sim
