#include "core/tracking/motor_velocity.hpp"

#include <sstream>
#include <stdexcept>

#include "core/tracking/clock.hpp"
#include "core/tracking/motor_position.hpp"

namespace marsokhod::tracking {

double velocity_radps_per_count(int con, int encoder_pulses_per_rev) {
  return encoder_rad_per_count(encoder_pulses_per_rev) / clock_overflow_period_s(con);
}

void require_velocity_counts(std::uint16_t vel) {
  if (vel > kVelocityMaxCounts) {
    std::ostringstream message;
    message << "invalid vel = " << vel
            << ": the velocity register has 15 bits (0..32767); decode the 0xi1 response with the "
               "protocol codec, which splits dir from vel";
    throw std::invalid_argument(message.str());
  }
}

double motor_velocity_radps(std::uint16_t vel, bool dir, int con, int encoder_pulses_per_rev) {
  require_velocity_counts(vel);
  const double speed_radps =
      velocity_radps_per_count(con, encoder_pulses_per_rev) * static_cast<double>(vel);
  return dir ? -speed_radps : speed_radps;
}

}  // namespace marsokhod::tracking
