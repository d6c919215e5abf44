#include "core/tracking/motor_position.hpp"

#include <numbers>

#include "core/tracking/counter.hpp"
#include "core/checks/checks.hpp"

namespace marsokhod::tracking {
namespace {

std::int32_t signed_difference(std::uint16_t later, std::uint16_t earlier) {
  return static_cast<std::int32_t>(counter_difference(later, earlier));
}

}  // namespace

PositionIncrement position_increment(const EncoderReading& previous,
                                     const EncoderReading& current) {
  PositionIncrement increment;
  const std::int32_t sign = previous.dir ? -1 : 1;
  const std::int32_t whole = signed_difference(current.enc, previous.enc);
  const std::int32_t before_reversal = signed_difference(current.stp, previous.enc);
  const std::int32_t after_reversal = signed_difference(current.enc, current.stp);
  // stp lies on the arc previous.enc → current.enc exactly when the two parts add up to the
  // whole arc; otherwise their sum is the arc plus 65536.
  const bool stp_on_arc = before_reversal + after_reversal == whole;
  if (current.dir == previous.dir) {
    if (current.stp != previous.stp && stp_on_arc) {
      // stp moved while dir stayed: an even number of direction changes since the last reading,
      // the last at stp. The pulses before it went both ways in an unknown split: net zero, the
      // midpoint; the pulses after it went in the direction dir reads.
      increment.hidden_reversals = true;
      increment.counts = sign * after_reversal;
      return increment;
    }
    increment.counts = sign * whole;
    return increment;
  }
  if (!stp_on_arc) {
    increment.reversal_point_unknown = true;
    return increment;
  }
  increment.counts = sign * (before_reversal - after_reversal);
  return increment;
}

double encoder_rad_per_count(int encoder_pulses_per_rev) {
  checks::setting::require_positive(static_cast<double>(encoder_pulses_per_rev),
                           "motors.encoder_pulses_per_rev");
  return 2.0 * std::numbers::pi / static_cast<double>(encoder_pulses_per_rev);
}

PositionTracker::PositionTracker(double initial_position_rad, int encoder_pulses_per_rev)
    : initial_position_rad_(initial_position_rad),
      rad_per_count_(encoder_rad_per_count(encoder_pulses_per_rev)),
      position_rad_(initial_position_rad) {
  checks::setting::require_finite(initial_position_rad, "motors.initial_position_rad");
}

double PositionTracker::update(const EncoderReading& reading) {
  if (started_) {
    const PositionIncrement increment = position_increment(previous_, reading);
    accumulated_counts_ += increment.counts;
    if (increment.reversal_point_unknown) {
      ++unknown_reversal_count_;
      uncertainty_counts_ += counter_difference(reading.enc, previous_.enc);
    }
    if (increment.hidden_reversals) {
      ++hidden_reversal_count_;
      uncertainty_counts_ += counter_difference(reading.stp, previous_.enc);
    }
  }
  started_ = true;
  previous_ = reading;
  position_rad_ = initial_position_rad_ + rad_per_count_ * static_cast<double>(accumulated_counts_);
  return position_rad_;
}

}  // namespace marsokhod::tracking
