#include "sim/electrics/battery.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace marsokhod::sim {
namespace {

void require(bool condition, const std::string& what) {
  if (!condition) {
    throw std::invalid_argument("battery: " + what + "; fix the SimTruth's power.battery");
  }
}

}  // namespace

Battery::Battery(const BatteryTruth& truth)
    : truth_(truth), state_of_charge_(std::clamp(truth.initial_state_of_charge, 0.0, 1.0)) {
  require(truth.capacity_ah > 0.0, "capacity_ah must be > 0");
  require(truth.blocks > 0, "blocks must be > 0");
  require(truth.polarisation_time_constant_s > 0.0, "polarisation_time_constant_s must be > 0");
  require(truth.resistance_full_ohm >= 0.0 && truth.resistance_empty_extra_ohm >= 0.0 &&
              truth.polarisation_resistance_ohm >= 0.0,
          "resistances must be ≥ 0");
}

double Battery::open_circuit_voltage_v() const {
  return truth_.blocks * (truth_.empty_block_v + truth_.block_v_per_charge * state_of_charge_);
}

double Battery::internal_resistance_ohm() const {
  const double empty_fraction = 1.0 - state_of_charge_;
  return truth_.resistance_full_ohm +
         truth_.resistance_empty_extra_ohm * empty_fraction * empty_fraction +
         extra_resistance_ohm_;
}

double Battery::terminal_voltage_v(double current_a) const {
  return open_circuit_voltage_v() - current_a * internal_resistance_ohm() - polarisation_v_;
}

double Battery::step(double current_a, double dt_s) {
  constexpr double kSecondsPerHour = 3600.0;
  state_of_charge_ = std::clamp(
      state_of_charge_ - current_a * dt_s / (kSecondsPerHour * truth_.capacity_ah), 0.0, 1.0);
  const double target_v = current_a * truth_.polarisation_resistance_ohm;
  const double decay = std::exp(-dt_s / truth_.polarisation_time_constant_s);
  polarisation_v_ = target_v + (polarisation_v_ - target_v) * decay;
  return terminal_voltage_v(current_a);
}

void Battery::set_extra_resistance_ohm(double resistance_ohm) {
  require(std::isfinite(resistance_ohm) && resistance_ohm >= 0.0,
          "the extra series resistance must be finite and ≥ 0 Ω");
  extra_resistance_ohm_ = resistance_ohm;
}

void Battery::set_state_of_charge(double state_of_charge) {
  require(std::isfinite(state_of_charge) && state_of_charge >= 0.0 && state_of_charge <= 1.0,
          "the state of charge must lie in 0..1");
  state_of_charge_ = state_of_charge;
}

}  // namespace marsokhod::sim
