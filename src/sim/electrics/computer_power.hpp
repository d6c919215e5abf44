// The onboard computer's supply (chapter 3.1, Field Experiment 6.2): below about 20 V the
// ReadyBoard reboots; 19.5 V was seen in the field.
//
// When the supply falls below brownout_v the computer goes off for reboot_s. While it is off it
// draws nothing (its 0.69 A of chapter 3.1's table drop out) and the driver it runs stops talking
// to the controllers: the simulated rover integration reads on() and mutes the driver. The reboot
// starts over as long as the supply stays below brownout_v. The controllers and µ8 are fed by
// their own converter and keep running with their last duty cycles; only µ8's dead man's switch
// (if armed) stops the motors then.
#pragma once

#include <cstdint>

namespace marsokhod::sim {

class ComputerPower {
 public:
  // Throws std::invalid_argument unless brownout_v is finite and reboot_s > 0.
  ComputerPower(double brownout_v, double reboot_s);

  // Feeds the supply voltage after a step of dt_s; returns on().
  bool update(double supply_v, double dt_s);
  // The brown-out fault: the computer goes off now as if the supply had dipped.
  void force_brownout();

  bool on() const { return off_remaining_s_ <= 0.0; }
  double off_remaining_s() const { return off_remaining_s_ > 0.0 ? off_remaining_s_ : 0.0; }
  std::uint64_t brownout_count() const { return brownout_count_; }
  double brownout_v() const { return brownout_v_; }

 private:
  double brownout_v_;
  double reboot_s_;
  double off_remaining_s_ = 0.0;
  std::uint64_t brownout_count_ = 0;
};

}  // namespace marsokhod::sim
