// The operator's commands (operator_commands.hpp) as the driver sees them: the latest valid
// input, checked against the ranges there and mapped to targets (Remark 5.7), and the 0.5 s rule
// of Field Experiment 6.7 — no valid input for operator_timeout_s ⇒ every target is zero and the
// rover comes to a controlled stop. An invalid input (NaN, out of range) is rejected with a
// reason and the last valid one stands until the timeout.
//
// A stop holds (an arming check, as on a hobby transmitter): after a stop — the STOP button of
// any console, a take-over or a release, which the link turns into stops — every target stays
// zero until the operator's input has been neutral (sticks centred, no gait speed, no joint
// button: is_neutral). Otherwise the controller's next 20 Hz reading, its stick still pushed,
// would drive on 50 ms after the stop. It lives here, not in the link, so that it holds for
// every transport, every scenario and in replay.
#pragma once

#include <optional>
#include <string>
#include <utility>

#include "core/mobility/gamepad.hpp"
#include "core/params.hpp"
#include "driver/operator_commands.hpp"

namespace marsokhod::driver {

// Neutral: no velocity, no gait speed, no joint button and no joint position asked for. The gait
// and calibration mode may stay selected: choosing them moves nothing.
bool is_neutral(const mobility::OperatorTargets& targets);

class OperatorChannel {
 public:
  explicit OperatorChannel(const Params& params);

  // Takes an input at time t; returns the reason if it was rejected (nothing changes then).
  std::optional<std::string> receive(const OperatorInput& input, double time_s);

  // The targets in force at time t: zero after the timeout, after a stop, or before any input.
  mobility::OperatorTargets targets(double time_s) const;
  bool timed_out(double time_s) const;
  // The operator asks for a stop: a stop not yet re-armed, the timeout, or no input yet.
  bool stopping(double time_s) const { return !armed_ || timed_out(time_s); }
  bool ever_received() const { return last_valid_s_.has_value(); }
  // True from a stop until a neutral input re-arms; then targets() are zero whatever is asked.
  bool stop_latched() const { return !armed_; }
  // Why the latest stop happened; kept after re-arming (empty before any stop).
  const std::string& stop_reason() const { return stop_reason_; }
  const std::string& last_rejection() const { return last_rejection_; }
  // The mission the latest input asked for, once: the driver starts it (core/navigation).
  std::optional<navigation::MissionRequest> take_mission() { return std::exchange(mission_, {}); }
  // The targets in force come from a cmd_vel (velocity input), armed and in time.
  bool velocity_in_force(double time_s) const {
    return velocity_ && armed_ && !timed_out(time_s);
  }

 private:
  const Params* params_;
  mobility::OperatorTargets current_;
  mobility::GamepadMemory memory_;
  std::optional<double> last_valid_s_;
  bool armed_ = true;  // no stop yet: the first input drives (scenarios, replay)
  std::string stop_reason_;
  std::string last_rejection_;
  std::optional<navigation::MissionRequest> mission_;
  bool velocity_ = false;  // current_ is a cmd_vel's
};

}  // namespace marsokhod::driver
