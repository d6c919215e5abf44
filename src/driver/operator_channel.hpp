// The operator's commands as the driver sees them: the latest valid input, checked and mapped to
// targets (Remark 5.7), and the 0.5 s rule of Field Experiment 6.7 — no valid input for
// operator_timeout_s ⇒ every target is zero and the rover comes to a controlled stop. An invalid
// input (NaN, out of range) is rejected with a reason and the last valid one stands until the
// timeout.
#pragma once

#include <optional>
#include <string>

#include "core/mobility/gamepad.hpp"
#include "core/params.hpp"

namespace marsokhod::driver {

// One operator message: a gamepad reading, or the targets of the mapping directly.
struct OperatorInput {
  std::optional<mobility::GamepadState> gamepad;
  std::optional<mobility::OperatorTargets> targets;  // memory is ignored
  bool stop = false;          // the console's stop: all targets zero until the next input
  bool clear_faults = false;  // acknowledge latched faults (silent controllers)
};

class OperatorChannel {
 public:
  explicit OperatorChannel(const Params& params);

  // Takes an input at time t; returns the reason if it was rejected (nothing changes then).
  std::optional<std::string> receive(const OperatorInput& input, double time_s);

  // The targets in force at time t: zero after the timeout, after a stop, or before any input.
  mobility::OperatorTargets targets(double time_s) const;
  bool timed_out(double time_s) const;
  // The operator asks for a stop: a stop message, the timeout, or no input yet.
  bool stopping(double time_s) const { return stopped_ || timed_out(time_s); }
  bool ever_received() const { return last_valid_s_.has_value(); }
  const std::string& last_rejection() const { return last_rejection_; }

 private:
  std::optional<std::string> check_targets(const mobility::OperatorTargets& t) const;

  const Params* params_;
  mobility::OperatorTargets current_;
  mobility::GamepadMemory memory_;
  std::optional<double> last_valid_s_;
  bool stopped_ = false;
  std::string last_rejection_;
};

}  // namespace marsokhod::driver
