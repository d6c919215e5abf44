// Chapter 3.2–3.3 for the motors: one 0xi1 response of µi (i = 0..7) and the con in force give
// the controller's time t (3.2), the accumulated shaft position p̄ and the velocity w̄ (3.3).
//
// Each controller has its own clock, so each motor has its own time axis; they all start at the
// same start_time_s on their first response. A cycle with a missing response simply skips that
// motor's update: time and position stay right as long as less than T(con) (32.8 ms at con = 0)
// and fewer than 65536 pulses pass between two responses that do arrive.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "core/params.hpp"
#include "core/protocol/messages.hpp"
#include "core/tracking/clock.hpp"
#include "core/tracking/motor_position.hpp"

namespace marsokhod::tracking {

struct MotorSample {
  double time_s = 0.0;          // t, (3.2)
  double position_rad = 0.0;    // p̄, chapter 3.2
  double velocity_radps = 0.0;  // w̄, (3.3)
};

class MotorTracker {
 public:
  // Throws std::invalid_argument if motor_index ≥ 8 or params are invalid (encoder pulses ≤ 0,
  // initial position not finite) or start_time_s is not finite.
  MotorTracker(const MotorParams& params, std::size_t motor_index, double start_time_s = 0.0);

  // Feeds µi's response; con is the register value in force since the previous response.
  // Throws std::invalid_argument if response.node is not this motor's index, con ∉ 0..255 or
  // vel exceeds 15 bits; the state is unchanged then.
  const MotorSample& update(const protocol::ControlResponse& response, int con);

  std::size_t motor_index() const { return motor_index_; }
  bool started() const { return clock_.started(); }
  const MotorSample& sample() const { return sample_; }
  const PositionTracker& position() const { return position_; }
  const ClockTracker& clock() const { return clock_; }

 private:
  std::size_t motor_index_;
  int encoder_pulses_per_rev_;
  ClockTracker clock_;
  PositionTracker position_;
  MotorSample sample_;
};

// The eight motors of the layout (3.1), indexed 0 FL … 7 AR.
struct MotorsSample {
  MotorVector time_s{};
  MotorVector position_rad{};
  MotorVector velocity_radps{};
};

class AllMotorsTracker {
 public:
  // Throws std::invalid_argument as MotorTracker does, naming the motor.
  explicit AllMotorsTracker(const MotorParams& params, double start_time_s = 0.0);

  // One full cycle: responses[i] must come from µi.
  const MotorsSample& update(const std::array<protocol::ControlResponse, kMotorCount>& responses,
                             int con);

  // One motor, chosen by response.node; for cycles in which some responses are missing.
  // Throws std::invalid_argument if response.node ≥ 8.
  const MotorSample& update_motor(const protocol::ControlResponse& response, int con);

  const MotorsSample& sample() const { return sample_; }
  const MotorTracker& motor(std::size_t motor_index) const { return motors_.at(motor_index); }

 private:
  std::array<MotorTracker, kMotorCount> motors_;
  MotorsSample sample_;
};

}  // namespace marsokhod::tracking
