// One AT90CAN128 running a real firmware image (.elf) in simavr at 16 MHz: the core of
// at90can128_core.h, its CAN controller (can_controller.hpp), pins and ADC inputs driven from
// outside, and time as a value (SimTimeNs ↔ cycles: 1 ns = 16/1000 cycles, 500 ns = 8 cycles).
// run_until() executes the firmware up to a time; between calls the caller changes inputs, which
// the firmware sees at exactly that time. Deterministic: the same inputs at the same times give
// the same outputs, bit for bit.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/protocol/can_frame.hpp"
#include "sim/avr/can_controller.hpp"
#include "sim/firmware/sim_time.hpp"

namespace marsokhod::sim::avr {

inline constexpr std::uint64_t kClockHz = 16'000'000;  // the thesis' timing needs 16 MHz
inline constexpr std::int64_t kAdcReferenceMillivolts = 5000;  // AVCC

struct TimedCanFrame {
  SimTimeNs time_ns = 0;
  protocol::CanFrame frame;
};

class AvrController {
 public:
  // Loads elf_path. Throws std::runtime_error naming the file when it cannot be read or is no
  // AVR image. boot_ns: how long the chip has run before time 0 (the firmware's start-up done);
  // its clocks, the CAN timer among them, count from its reset.
  explicit AvrController(const std::string& elf_path, SimTimeNs boot_ns = 0);
  ~AvrController();
  AvrController(const AvrController&) = delete;
  AvrController& operator=(const AvrController&) = delete;

  // Runs the firmware until its clock reaches time_ns (at most one instruction beyond it; a time
  // already passed does nothing). Throws
  // std::runtime_error if the core crashed (bad opcode, stack overflow).
  void run_until(SimTimeNs time_ns);
  SimTimeNs time_ns() const;
  std::uint64_t cycle() const;

  // A frame from the bus now: true if a message object took it.
  bool deliver(const protocol::CanFrame& frame);
  // The frames sent since the last call, stamped with the time the firmware queued them.
  std::vector<TimedCanFrame> take_transmitted();

  // Drives an input pin (port 'A'..'G', pin 0..7) to a level now.
  void set_pin(char port, int pin, bool high);
  // The ADC input channel (0..7) to the voltage that converts to counts (0..1023).
  void set_adc_counts(int channel, std::uint16_t counts);
  // A data-space register (I/O and extended I/O), e.g. 0x8A for OCR1BL; 16-bit at low, low+1.
  std::uint8_t register8(std::uint16_t address) const;
  std::uint16_t register16(std::uint16_t low_address) const;
  std::uint16_t can_timer() const { return can_->timer(); }
  avr_t* core() { return core_; }

 private:
  SimTimeNs boot_ns_;
  avr_t* core_ = nullptr;
  std::unique_ptr<CanController> can_;
  // simavr finds an IRQ by a linear search over its I/O modules: looked up once.
  std::array<std::array<avr_irq_t*, 8>, 7> port_irqs_{};  // ports A..G, pins 0..7
  std::array<avr_irq_t*, 8> adc_irqs_{};
  std::array<std::uint32_t, 8> adc_millivolts_{};
};

std::uint64_t cycles_at(SimTimeNs time_ns);

}  // namespace marsokhod::sim::avr
