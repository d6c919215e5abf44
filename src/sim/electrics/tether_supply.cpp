#include "sim/electrics/tether_supply.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace marsokhod::sim {

TetherSupply::TetherSupply(const TetherTruth& truth) : truth_(truth) {
  if (!(truth.set_v >= 0.0 && truth.set_v <= 30.0) || !(truth.current_limit_a > 0.0) ||
      !(truth.cable_resistance_ohm >= 0.0) || !(truth.foldback_ohm_per_a >= 0.0)) {
    throw std::invalid_argument(
        "tether supply: set_v must lie in 0..30 V, current_limit_a be > 0 and the resistances "
        "≥ 0; fix the SimTruth's power.tether");
  }
}

double TetherSupply::terminal_voltage_v(double current_a) const {
  const double over_limit_a = std::max(0.0, current_a - truth_.current_limit_a);
  const double voltage_v = truth_.set_v -
                           current_a * (truth_.cable_resistance_ohm + extra_resistance_ohm_) -
                           truth_.foldback_ohm_per_a * over_limit_a;
  return std::max(0.0, voltage_v);
}

double TetherSupply::step(double current_a, double /*dt_s*/) const {
  return terminal_voltage_v(current_a);
}

void TetherSupply::set_voltage(double set_v) {
  if (!(set_v >= 0.0 && set_v <= 30.0)) {
    throw std::invalid_argument("tether supply: the set voltage must lie in 0..30 V");
  }
  truth_.set_v = set_v;
}

void TetherSupply::set_extra_resistance_ohm(double resistance_ohm) {
  if (!std::isfinite(resistance_ohm) || resistance_ohm < 0.0) {
    throw std::invalid_argument("tether supply: the extra resistance must be finite and ≥ 0 Ω");
  }
  extra_resistance_ohm_ = resistance_ohm;
}

}  // namespace marsokhod::sim
