#include "sim/electrics/computer_power.hpp"

#include <cmath>
#include <stdexcept>

namespace marsokhod::sim {

ComputerPower::ComputerPower(double brownout_v, double reboot_s)
    : brownout_v_(brownout_v), reboot_s_(reboot_s) {
  if (!std::isfinite(brownout_v) || !(reboot_s > 0.0) || !std::isfinite(reboot_s)) {
    throw std::invalid_argument(
        "computer power: brownout_v must be finite and reboot_s > 0; fix the SimTruth's power");
  }
}

bool ComputerPower::update(double supply_v, double dt_s) {
  if (supply_v < brownout_v_) {
    if (on()) {
      ++brownout_count_;
    }
    off_remaining_s_ = reboot_s_;  // the boot only completes on a steady supply
    return false;
  }
  if (!on()) {
    off_remaining_s_ -= dt_s;
  }
  return on();
}

void ComputerPower::force_brownout() {
  if (on()) {
    ++brownout_count_;
  }
  off_remaining_s_ = reboot_s_;
}

}  // namespace marsokhod::sim
