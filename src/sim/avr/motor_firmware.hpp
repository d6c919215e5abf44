// A motor controller µ0–µ7 running its real firmware (firmware/motor.c, image muN.elf) in simavr,
// driven like the emulation (sim/firmware/motor_controller.hpp): the shaft angle over time and
// frames from the bus.
//
// The encoder: the shaft's pulse boundaries k·2π/pulses_per_rev, crossed on the straight line
// between two samples, as the emulation counts them. For each crossing the LS7184 model first
// sets its direction line (INT0, PD0: high while the shaft turns negative) when the direction
// changed, and kPulseDelayNs later gives T3 (PE6) a rising edge, 1 µs wide: the firmware's INT0
// handler reads enc before the pulse it announces (the emulation's stp = enc before that pulse).
// Pulses are therefore seen kPulseDelayNs after the emulation counts them.
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "sim/avr/avr_controller.hpp"
#include "sim/electrics/seeded_random.hpp"

namespace marsokhod::sim::avr {

inline constexpr SimTimeNs kPulseDelayNs = 4000;
inline constexpr SimTimeNs kPulseWidthNs = 1000;

class MotorFirmware {
 public:
  // Throws like AvrController, and std::invalid_argument for pulses_per_rev ≤ 0.
  // seed: the draws of the lost pulses (set_lost_pulse_fraction).
  MotorFirmware(const std::string& elf_path, double initial_shaft_angle_rad, int pulses_per_rev,
                std::uint64_t seed = 0, SimTimeNs boot_ns = 0);

  // Runs the firmware to time_ns while the shaft moves linearly to shaft_angle_rad.
  void advance(SimTimeNs time_ns, double shaft_angle_rad);
  // A frame from the bus at the current time (the answer comes out of take_transmitted() after
  // the next advance). False if no message object took it (the acceptance filter).
  bool deliver(const protocol::CanFrame& frame) { return controller_.deliver(frame); }
  std::vector<TimedCanFrame> take_transmitted() { return controller_.take_transmitted(); }

  // d = (−1)^drv·pwm/icr from the firmware's registers: OCR1B, ICR1 and PC2.
  double duty() const;
  int icr() const;
  // The loose encoder connection: each pulse is lost with this probability (0 = healthy); the
  // LS7184 still announces direction changes. Throws std::invalid_argument outside 0..1.
  void set_lost_pulse_fraction(double fraction);
  // Pulses given to T3 so far (to check a test's trajectory).
  std::uint64_t pulses() const { return pulses_; }
  AvrController& controller() { return controller_; }

 private:
  struct PinEvent {
    SimTimeNs time_ns;
    char port;
    int pin;
    bool high;
  };
  void schedule_crossings(SimTimeNs time_ns, double shaft_angle_rad);

  AvrController controller_;
  double pulses_per_rad_;
  double shaft_angle_rad_;
  std::int64_t pulse_index_;
  bool line_negative_ = false;
  std::deque<PinEvent> events_;
  SimTimeNs time_ns_ = 0;  // of the last advance (the core may have run a few cycles past it)
  std::uint64_t pulses_ = 0;
  double lost_pulse_fraction_ = 0.0;
  SeededRandom random_;
};

}  // namespace marsokhod::sim::avr
