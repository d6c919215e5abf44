#include "driver/operator_channel.hpp"

#include <stdexcept>

namespace marsokhod::driver {

bool is_neutral(const mobility::OperatorTargets& t) {
  const auto& b = t.joint_buttons;
  return t.v1_radps == 0.0 && t.v2_radps == 0.0 && t.v3_radps == 0.0 &&
         t.v4_radps == 0.0 && t.v6_radps == 0.0 &&
         t.v7_radps == 0.0 && t.gait_speed == 0.0 && !b.contract_front && !b.extend_front &&
         !b.contract_rear && !b.extend_rear && !t.front_joint_target_rad &&
         !t.rear_joint_target_rad;
}

OperatorChannel::OperatorChannel(const Params& params) : params_(&params) {}

std::optional<std::string> OperatorChannel::receive(const OperatorInput& input, double time_s) {
  mobility::OperatorTargets next = current_;
  const int commands = static_cast<int>(input.gamepad.has_value()) +
                       static_cast<int>(input.targets.has_value()) +
                       static_cast<int>(input.velocity.has_value()) +
                       static_cast<int>(input.mission.has_value()) +
                       static_cast<int>(input.heartbeat);
  if (commands > 1) {
    last_rejection_ =
        "an operator input carries one of a gamepad reading, targets, a velocity, a mission or a "
        "heartbeat, not several";
    return last_rejection_;
  }
  // clear_faults alone changes no target and does not count as the operator's command.
  if (commands == 0 && !input.stop) {
    if (input.clear_faults) return std::nullopt;
    last_rejection_ =
        "an operator input carries a gamepad reading, targets, a velocity, a mission, a heartbeat "
        "or a stop";
    return last_rejection_;
  }
  // A velocity, a mission and a heartbeat leave the gait and calibration mode as they were.
  mobility::OperatorTargets still;
  still.gait = current_.gait;
  still.calibration_mode = current_.calibration_mode;
  still.memory = memory_;
  if (input.velocity) {
    if (auto e = navigation::check_velocity(*input.velocity, *params_)) {
      last_rejection_ = e->message;
      return last_rejection_;
    }
    const navigation::DriveTargets t = navigation::velocity_targets(*input.velocity, *params_);
    next = still;
    next.gait = mobility::Gait::kNone;  // cmd_vel drives on wheels
    next.v1_radps = t.v1_radps;
    next.v2_radps = t.v2_radps;
  } else if (input.mission) {
    if (auto e = navigation::check_request(*input.mission)) {
      last_rejection_ = e->message;
      return last_rejection_;
    }
    next = still;
    next.gait = mobility::Gait::kNone;
  } else if (input.heartbeat) {
    // Carry on: a cmd_vel stays in force (a velocity mission is kept alive like the others);
    // anything else becomes neutral.
    next = velocity_ ? current_ : still;
  } else if (input.gamepad) {
    try {
      next = mobility::map_gamepad(*input.gamepad, params_->operator_input, memory_);
    } catch (const std::invalid_argument& e) {
      last_rejection_ = e.what();
      return last_rejection_;
    }
  } else if (input.targets) {
    if (auto e = check_targets(*input.targets, *params_)) {
      last_rejection_ = e->message;
      return last_rejection_;
    }
    next = *input.targets;
    next.memory = memory_;
  }
  memory_ = next.memory;
  current_ = next;
  last_valid_s_ = time_s;
  if (input.velocity || input.gamepad || input.targets) velocity_ = input.velocity.has_value();
  if (input.mission) {
    mission_ = input.mission;
    velocity_ = false;
  }
  if (input.stop) {
    armed_ = false;
    stop_reason_ = input.stop_reason.empty() ? "stop" : input.stop_reason;
  } else if (!armed_ && is_neutral(next)) {
    armed_ = true;  // the operator let go: the next input drives
  }
  // A non-neutral input while latched is taken (its gait choice and button edges count, it
  // renews the timeout) but moves nothing: targets() stay zero until the operator lets go.
  return std::nullopt;
}

bool OperatorChannel::timed_out(double time_s) const {
  return !last_valid_s_ || time_s - *last_valid_s_ > params_->safety.operator_timeout_s;
}

mobility::OperatorTargets OperatorChannel::targets(double time_s) const {
  if (!armed_ || timed_out(time_s)) {
    mobility::OperatorTargets zero;
    zero.gait = current_.gait;  // the gait stays selected; its speed is zero
    // Calibration mode stays too (with no button held): leaving it resets the joint positions,
    // which only the operator may ask for.
    zero.calibration_mode = current_.calibration_mode;
    zero.memory = memory_;
    return zero;
  }
  return current_;
}

}  // namespace marsokhod::driver
