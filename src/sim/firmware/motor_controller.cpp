#include "sim/firmware/motor_controller.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <variant>

#include "core/protocol/codec.hpp"

namespace marsokhod::sim {
namespace {

constexpr std::uint16_t kMaxVelCounts = 0x7FFF;  // vel is a 15-bit field of 0xi1

std::int64_t pulse_index(double shaft_angle_rad, double pulses_per_rad) {
  return static_cast<std::int64_t>(std::floor(shaft_angle_rad * pulses_per_rad));
}

}  // namespace

MotorController::MotorController(std::uint8_t node, double initial_shaft_angle_rad,
                                 int pulses_per_rev, std::uint64_t seed, int velocity_window_slices)
    : node_(node),
      pulses_per_rad_(pulses_per_rev / (2.0 * std::numbers::pi)),
      shaft_angle_rad_(initial_shaft_angle_rad),
      pulse_index_(pulse_index(initial_shaft_angle_rad, pulses_per_rad_)),
      slice_ticks_(velocity_window_slices > 0 ? kTimerModulus / velocity_window_slices : 0),
      slice_pulses_(velocity_window_slices > 0 ? velocity_window_slices : 0, 0),
      random_(seed) {
  if (node >= protocol::kMotorControllerCount || pulses_per_rev <= 0) {
    throw std::invalid_argument("motor controller: node " + std::to_string(node) +
                                " must be 0..7 and the encoder pulses per revolution > 0");
  }
  const bool power_of_two =
      velocity_window_slices > 0 && (velocity_window_slices & (velocity_window_slices - 1)) == 0;
  if (!power_of_two || velocity_window_slices > 256) {
    throw std::invalid_argument(
        "motor controller: velocity_window_slices = " + std::to_string(velocity_window_slices) +
        " must be a power of two in 1..256 (it divides tim's 65536)");
  }
}

std::uint64_t MotorController::ticks_at(SimTimeNs time_ns) const {
  return ticks_before_epoch_ + static_cast<std::uint64_t>((time_ns - epoch_start_ns_) / tick_ns());
}

SimTimeNs MotorController::next_slice_end_ns() const {
  const std::uint64_t end_ticks = (ticks_at(time_ns_) / slice_ticks_ + 1) * slice_ticks_;
  return epoch_start_ns_ + static_cast<SimTimeNs>(end_ticks - ticks_before_epoch_) * tick_ns();
}

void MotorController::close_slice() {
  slice_pulses_[next_slice_] = pulses_this_slice_;
  next_slice_ = (next_slice_ + 1) % slice_pulses_.size();
  pulses_this_slice_ = 0;
  std::uint64_t window_pulses = 0;
  for (const std::uint64_t pulses : slice_pulses_) {
    window_pulses += pulses;
  }
  registers_.vel =
      static_cast<std::uint16_t>(std::min<std::uint64_t>(window_pulses, kMaxVelCounts));
}

void MotorController::advance(SimTimeNs time_ns, double shaft_angle_rad) {
  if (time_ns < time_ns_) {
    throw std::invalid_argument("motor controller: time must not go back (" +
                                std::to_string(time_ns) + " ns < " + std::to_string(time_ns_) +
                                " ns)");
  }
  for (SimTimeNs slice_end_ns = next_slice_end_ns(); slice_end_ns <= time_ns;
       slice_end_ns = next_slice_end_ns()) {
    // The shaft angle at the slice's end, on the straight line between the two samples.
    const double fraction =
        static_cast<double>(slice_end_ns - time_ns_) / static_cast<double>(time_ns - time_ns_);
    move_shaft_to(shaft_angle_rad_ + (shaft_angle_rad - shaft_angle_rad_) * fraction);
    time_ns_ = slice_end_ns;
    close_slice();
  }
  move_shaft_to(shaft_angle_rad);
  time_ns_ = time_ns;
}

void MotorController::move_shaft_to(double shaft_angle_rad) {
  const std::int64_t index = pulse_index(shaft_angle_rad, pulses_per_rad_);
  const std::int64_t crossed = index - pulse_index_;
  if (crossed != 0) {
    count_pulses(crossed < 0 ? -crossed : crossed, crossed < 0);
  }
  pulse_index_ = index;
  shaft_angle_rad_ = shaft_angle_rad;
}

void MotorController::count_pulses(std::int64_t pulses, bool negative) {
  if (negative != line_negative_) {
    line_negative_ = negative;
    if (registers_.eim) {  // INT0 unmasked: the firmware records the measured change
      registers_.stp = registers_.enc;
      registers_.dir = negative;
    }
  }
  std::int64_t counted = pulses;
  if (lost_pulse_fraction_ > 0.0) {
    counted = 0;
    for (std::int64_t i = 0; i < pulses; ++i) {
      counted += random_.bernoulli(lost_pulse_fraction_) ? 0 : 1;
    }
  }
  registers_.enc = static_cast<std::uint16_t>(
      (registers_.enc + static_cast<std::uint64_t>(counted)) % kTimerModulus);
  pulses_this_slice_ += static_cast<std::uint64_t>(counted);
}

void MotorController::change_con(std::uint8_t con) {
  ticks_before_epoch_ = ticks_at(time_ns_);
  epoch_start_ns_ = time_ns_;
  registers_.con = con;
}

MotorControllerRegisters MotorController::registers() const {
  MotorControllerRegisters registers = registers_;
  registers.tim = static_cast<std::uint16_t>(ticks_at(time_ns_) % kTimerModulus);
  return registers;
}

double MotorController::duty() const {
  const double magnitude = static_cast<double>(registers_.pwm) / registers_.icr;
  return registers_.drv ? -magnitude : magnitude;
}

std::optional<protocol::CanFrame> MotorController::receive(const protocol::CanFrame& frame) {
  const std::uint32_t idt = frame.id >> 3;
  if ((idt >> 4) != node_) {
    return std::nullopt;  // the acceptance filter passes this node's identifiers only
  }
  protocol::DecodeContext context;
  context.icr[node_] = registers_.icr;
  const protocol::DecodeResult decoded = protocol::decode(frame, context);
  if (!decoded) {
    return std::nullopt;
  }
  const MotorControllerRegisters now = registers();
  if (const auto* control = std::get_if<protocol::ControlRequest>(&decoded.message())) {
    registers_.drv = control->drv;
    registers_.eim = control->eim;
    registers_.pwm = control->pwm;
    return protocol::encode(
        protocol::ControlResponse{node_, now.tim, now.enc, now.stp, now.dir, now.vel});
  }
  if (const auto* config = std::get_if<protocol::ConfigurationRequest>(&decoded.message())) {
    if (config->con != registers_.con) {
      change_con(config->con);
    }
    registers_.icr = config->icr;
    registers_.pwm = config->pwm;
    return protocol::encode(protocol::ConfigurationResponse{node_, now.tim});
  }
  return std::nullopt;  // a response of another kind: not for this firmware
}

void MotorController::set_lost_pulse_fraction(double fraction) {
  if (!(fraction >= 0.0 && fraction <= 1.0)) {
    throw std::invalid_argument("motor controller: the lost pulse fraction must lie in 0..1");
  }
  lost_pulse_fraction_ = fraction;
}

}  // namespace marsokhod::sim
