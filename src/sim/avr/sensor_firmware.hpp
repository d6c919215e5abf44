// The sensor controller µ8 running its real firmware (firmware/sensor.c, image mu8.elf) in
// simavr: the seven analog inputs as ADC counts, the LEDs read from the pins, and on request the
// 16-character display through simavr's HD44780 part wired to port A as chapter 3.3's pin table
// has it (D4–D7 on PA4–PA7, E on PA2, R/W on PA1, RS on PA0). The part prints every byte it
// receives on standard output, which `scenario --json` needs for itself: the rover's µ8
// (rover_hardware.hpp) runs without it, as the simulator shows no display anyway.
#pragma once

extern "C" {  // simavr's parts headers declare C functions without extern "C" of their own
#include <simavr/parts/hd44780.h>
}

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/avr/avr_controller.hpp"

namespace marsokhod::sim::avr {

// What the ADC converts, in counts 0..1023 (the channel order of chapter 3.3: ADC0 yaw, ADC1–3
// acc¹⁻³, ADC4 front tilt, ADC5 rear tilt, ADC6 supply).
struct SensorCounts {
  std::uint16_t yaw = 0;
  std::array<std::uint16_t, 3> acc{};
  std::uint16_t tilt_front = 0;
  std::uint16_t tilt_rear = 0;
  std::uint16_t vcc = 0;
};

class SensorFirmware {
 public:
  explicit SensorFirmware(const std::string& elf_path, bool with_display = false,
                          SimTimeNs boot_ns = 0);

  void advance(SimTimeNs time_ns) { controller_.run_until(time_ns); }
  // The inputs from now on (the firmware's ADC ring converts one channel every 104 µs).
  void set_inputs(const SensorCounts& counts);
  bool deliver(const protocol::CanFrame& frame) { return controller_.deliver(frame); }
  std::vector<TimedCanFrame> take_transmitted() { return controller_.take_transmitted(); }

  bool green_led() const;  // led⁰ on PB6, on when high
  bool white_led() const;  // led¹ on PE3 with a pull-up, on when low
  // The first line of the display, 16 characters; empty without the display.
  std::string display() const;
  AvrController& controller() { return controller_; }

 private:
  AvrController controller_;
  bool with_display_;
  hd44780_t lcd_{};
};

}  // namespace marsokhod::sim::avr
