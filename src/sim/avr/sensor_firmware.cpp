#include "sim/avr/sensor_firmware.hpp"

#include <simavr/avr_ioport.h>
#include <simavr/sim_irq.h>

namespace marsokhod::sim::avr {
namespace {

constexpr std::uint16_t kPortb = 0x25;
constexpr std::uint16_t kPorte = 0x2E;
constexpr std::uint8_t kGreenPin = 1U << 6;
constexpr std::uint8_t kWhitePin = 1U << 3;

}  // namespace

SensorFirmware::SensorFirmware(const std::string& elf_path, bool with_display,
                               SimTimeNs boot_ns)
    : controller_(elf_path, boot_ns), with_display_(with_display) {
  if (!with_display_) {
    return;
  }
  avr_t* core = controller_.core();
  hd44780_init(core, &lcd_, 16, 2);
  const auto pin = [core](int number) {
    return avr_io_getirq(core, AVR_IOCTL_IOPORT_GETIRQ('A'), number);
  };
  for (int data = 0; data < 4; ++data) {
    avr_connect_irq(pin(4 + data), lcd_.irq + IRQ_HD44780_D4 + data);
  }
  avr_connect_irq(pin(0), lcd_.irq + IRQ_HD44780_RS);
  avr_connect_irq(pin(1), lcd_.irq + IRQ_HD44780_RW);
  avr_connect_irq(pin(2), lcd_.irq + IRQ_HD44780_E);
}

void SensorFirmware::set_inputs(const SensorCounts& counts) {
  controller_.set_adc_counts(0, counts.yaw);
  for (int axis = 0; axis < 3; ++axis) {
    controller_.set_adc_counts(1 + axis, counts.acc[static_cast<std::size_t>(axis)]);
  }
  controller_.set_adc_counts(4, counts.tilt_front);
  controller_.set_adc_counts(5, counts.tilt_rear);
  controller_.set_adc_counts(6, counts.vcc);
}

bool SensorFirmware::green_led() const { return controller_.register8(kPortb) & kGreenPin; }
bool SensorFirmware::white_led() const { return !(controller_.register8(kPorte) & kWhitePin); }

std::string SensorFirmware::display() const {
  if (!with_display_) {
    return {};
  }
  return std::string(lcd_.vram, lcd_.vram + 16);
}

}  // namespace marsokhod::sim::avr
