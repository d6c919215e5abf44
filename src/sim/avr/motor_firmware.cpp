#include "sim/avr/motor_firmware.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace marsokhod::sim::avr {
namespace {

constexpr std::uint16_t kOcr1b = 0x8A;  // OCR1BL, OCR1BH
constexpr std::uint16_t kIcr1 = 0x86;   // ICR1L, ICR1H
constexpr std::uint16_t kPortc = 0x28;  // PORTC: PC2 = drv
constexpr std::uint8_t kDrvPin = 1U << 2;

std::int64_t pulse_index(double shaft_angle_rad, double pulses_per_rad) {
  return static_cast<std::int64_t>(std::floor(shaft_angle_rad * pulses_per_rad));
}

}  // namespace

MotorFirmware::MotorFirmware(const std::string& elf_path, double initial_shaft_angle_rad,
                             int pulses_per_rev, std::uint64_t seed, SimTimeNs boot_ns)
    : controller_(elf_path, boot_ns),
      pulses_per_rad_(pulses_per_rev / (2.0 * std::numbers::pi)),
      shaft_angle_rad_(initial_shaft_angle_rad),
      pulse_index_(pulse_index(initial_shaft_angle_rad, pulses_per_rad_)),
      random_(seed) {
  if (pulses_per_rev <= 0) {
    throw std::invalid_argument("motor firmware: the encoder pulses per revolution must be > 0");
  }
}

void MotorFirmware::schedule_crossings(SimTimeNs time_ns, double shaft_angle_rad) {
  const SimTimeNs start_ns = time_ns_;
  const std::int64_t index = pulse_index(shaft_angle_rad, pulses_per_rad_);
  const bool negative = index < pulse_index_;
  const double span_rad = shaft_angle_rad - shaft_angle_rad_;
  for (std::int64_t i = pulse_index_; i != index; i += negative ? -1 : 1) {
    // Crossing up from i to i+1 at angle (i+1)/ppr; down from i to i−1 at angle i/ppr.
    const double boundary_rad = static_cast<double>(negative ? i : i + 1) / pulses_per_rad_;
    const double fraction = (boundary_rad - shaft_angle_rad_) / span_rad;
    const SimTimeNs at_ns =
        start_ns + static_cast<SimTimeNs>(std::ceil(fraction * static_cast<double>(time_ns - start_ns)));
    if (negative != line_negative_) {
      line_negative_ = negative;
      events_.push_back({at_ns, 'D', 0, negative});
    }
    if (lost_pulse_fraction_ > 0.0 && random_.bernoulli(lost_pulse_fraction_)) {
      continue;
    }
    events_.push_back({at_ns + kPulseDelayNs, 'E', 6, true});
    events_.push_back({at_ns + kPulseDelayNs + kPulseWidthNs, 'E', 6, false});
  }
  pulse_index_ = index;
  shaft_angle_rad_ = shaft_angle_rad;
}

void MotorFirmware::advance(SimTimeNs time_ns, double shaft_angle_rad) {
  if (time_ns < time_ns_) {
    throw std::invalid_argument("motor firmware: time must not go back (" +
                                std::to_string(time_ns) + " ns < " + std::to_string(time_ns_) +
                                " ns)");
  }
  schedule_crossings(time_ns, shaft_angle_rad);
  time_ns_ = time_ns;
  // Events of one sample are in time order, and every new one lies after the older ones.
  while (!events_.empty() && events_.front().time_ns <= time_ns) {
    const PinEvent event = events_.front();
    events_.pop_front();
    controller_.run_until(event.time_ns);
    controller_.set_pin(event.port, event.pin, event.high);
    if (event.port == 'E' && event.high) {
      ++pulses_;
    }
  }
  controller_.run_until(time_ns);
}

double MotorFirmware::duty() const {
  const double icr = controller_.register16(kIcr1);
  const double magnitude = icr > 0 ? controller_.register16(kOcr1b) / icr : 0.0;
  return (controller_.register8(kPortc) & kDrvPin) ? -magnitude : magnitude;
}

}  // namespace marsokhod::sim::avr

namespace marsokhod::sim::avr {

int MotorFirmware::icr() const { return controller_.register16(kIcr1); }

void MotorFirmware::set_lost_pulse_fraction(double fraction) {
  if (!(fraction >= 0.0 && fraction <= 1.0)) {
    throw std::invalid_argument("motor firmware: the lost pulse fraction must lie in 0..1");
  }
  lost_pulse_fraction_ = fraction;
}

}  // namespace marsokhod::sim::avr
