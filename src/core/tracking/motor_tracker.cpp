#include "core/tracking/motor_tracker.hpp"

#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/tracking/motor_velocity.hpp"
#include "core/checks/checks.hpp"

namespace marsokhod::tracking {
namespace {

std::size_t checked_motor_index(std::size_t motor_index) {
  if (motor_index >= kMotorCount) {
    std::ostringstream message;
    message << "invalid motor index " << motor_index << ": µ0–µ7 drive motors 0..7 (µ8 is the "
            << "sensor node); track µ8's responses with SensorTracker";
    throw std::invalid_argument(message.str());
  }
  return motor_index;
}

double initial_position(const MotorParams& params, std::size_t motor_index) {
  const double position_rad = params.initial_position_rad[checked_motor_index(motor_index)];
  checks::setting::require_finite(position_rad,
                         "motors.initial_position_rad[" + std::to_string(motor_index) + "]");
  return position_rad;
}

template <std::size_t... Index>
std::array<MotorTracker, kMotorCount> make_motors(const MotorParams& params, double start_time_s,
                                                  std::index_sequence<Index...>) {
  return {MotorTracker(params, Index, start_time_s)...};
}

}  // namespace

MotorTracker::MotorTracker(const MotorParams& params, std::size_t motor_index, double start_time_s)
    : motor_index_(checked_motor_index(motor_index)),
      encoder_pulses_per_rev_(params.encoder_pulses_per_rev),
      clock_(start_time_s),
      position_(initial_position(params, motor_index), params.encoder_pulses_per_rev) {
  sample_.time_s = start_time_s;
  sample_.position_rad = position_.position_rad();
}

const MotorSample& MotorTracker::update(const protocol::ControlResponse& response, int con) {
  if (response.node != motor_index_) {
    std::ostringstream message;
    message << "response from node " << static_cast<int>(response.node)
            << " given to the tracker of motor " << motor_index_
            << ": route each 0xi1 response to the tracker of motor i";
    throw std::invalid_argument(message.str());
  }
  // Computed first: it rejects a bad con or vel before the clock or position change.
  const double velocity_radps =
      motor_velocity_radps(response.vel, response.dir, con, encoder_pulses_per_rev_);
  sample_.time_s = clock_.update(response.tim, con);
  sample_.position_rad = position_.update({response.enc, response.stp, response.dir});
  sample_.velocity_radps = velocity_radps;
  return sample_;
}

AllMotorsTracker::AllMotorsTracker(const MotorParams& params, double start_time_s)
    : motors_(make_motors(params, start_time_s, std::make_index_sequence<kMotorCount>{})) {
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    sample_.time_s[i] = motors_[i].sample().time_s;
    sample_.position_rad[i] = motors_[i].sample().position_rad;
  }
}

const MotorsSample& AllMotorsTracker::update(
    const std::array<protocol::ControlResponse, kMotorCount>& responses, int con) {
  // Check the whole cycle before touching any motor, so a bad response leaves all unchanged.
  checks::setting::require_con(con);
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    if (responses[i].node != i) {
      std::ostringstream message;
      message << "responses[" << i << "] comes from node " << static_cast<int>(responses[i].node)
              << ": put µi's 0xi1 response at index i, or use update_motor()";
      throw std::invalid_argument(message.str());
    }
    require_velocity_counts(responses[i].vel);
  }
  for (const protocol::ControlResponse& response : responses) {
    update_motor(response, con);
  }
  return sample_;
}

const MotorSample& AllMotorsTracker::update_motor(const protocol::ControlResponse& response,
                                                  int con) {
  const std::size_t i = checked_motor_index(response.node);
  const MotorSample& motor_sample = motors_[i].update(response, con);
  sample_.time_s[i] = motor_sample.time_s;
  sample_.position_rad[i] = motor_sample.position_rad;
  sample_.velocity_radps[i] = motor_sample.velocity_radps;
  return motor_sample;
}

}  // namespace marsokhod::tracking
