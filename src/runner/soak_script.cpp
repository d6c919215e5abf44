#include "runner/soak_script.hpp"

#include <algorithm>
#include <cmath>

namespace marsokhod::runner {
namespace {

constexpr double kDroppedMessage = 0.2;  // a console message lost or late: ~51 of 64 per second

// How often each activity is chosen, in Activity's order.
constexpr std::array<double, kActivityCount> kWeights{3, 2, 1, 2, 2, 1, 3, 1, 1, 2, 1, 2};

// A mission's size: turns up to half a turn, moves and goto's legs up to 1.5 m each way.
constexpr double kMissionTurnRad = 3.14;
constexpr double kMissionReachM = 1.5;

constexpr std::array<mobility::Gait, 5> kGaits{
    mobility::Gait::kRolking, mobility::Gait::kFrontWheelWalking,
    mobility::Gait::kRearWheelWalking, mobility::Gait::kWormLike,
    mobility::Gait::kRolkingExtendedBase};

// The gamepad button that selects each gait of kGaits (docs/gamepad.md).
constexpr std::array<std::size_t, 5> kGaitButtons{
    mobility::kDpadUp, mobility::kDpadRight, mobility::kDpadLeft, mobility::kDpadDown,
    mobility::kButtonTop};

}  // namespace

double SoakRandom::uniform(double lo, double hi) {
  return lo + (hi - lo) * static_cast<double>(engine_() >> 11) * 0x1.0p-53;
}

std::size_t SoakRandom::below(std::size_t n) {
  return std::min(n - 1, static_cast<std::size_t>(uniform(0.0, static_cast<double>(n))));
}

std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (stream + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

const char* activity_name(Activity activity) {
  switch (activity) {
    case Activity::kDrive: return "drive";
    case Activity::kSpin: return "spin";
    case Activity::kTrench: return "trench";
    case Activity::kDriveAndSpin: return "drive-and-spin";
    case Activity::kJoints: return "joints";
    case Activity::kJointTargets: return "joint-targets";
    case Activity::kGait: return "gait";
    case Activity::kStop: return "stop";
    case Activity::kHandOver: return "hand-over";
    case Activity::kSilence: return "silence";
    case Activity::kVelocity: return "velocity";
    case Activity::kMission: return "mission";
  }
  return "?";
}

OperatorScript::OperatorScript(std::uint64_t seed, const Params& params)
    : params_(&params), random_(seed) {}

// A turn, a move or a goto of 1–3 waypoints around the pose the driver reports; a third of them
// with their own standing (1–10 s).
navigation::MissionRequest OperatorScript::random_mission(const driver::DriverStatus& status) {
  navigation::MissionRequest m;
  const std::size_t kind = random_.below(3);
  // Never exactly 0: a turn or move of nothing is still a mission, but a useless one.
  const double sign = random_.chance(0.5) ? 1.0 : -1.0;
  if (kind == 0) {
    m.kind = navigation::MissionKind::kTurn;
    m.angle_rad = sign * random_.uniform(0.1, kMissionTurnRad);
  } else if (kind == 1) {
    m.kind = navigation::MissionKind::kMove;
    m.distance_m = sign * random_.uniform(0.1, kMissionReachM);
  } else {
    m.kind = navigation::MissionKind::kGoto;
    double x = status.pose.x_m, y = status.pose.y_m;
    const std::size_t count = 1 + random_.below(3);
    const double limit = 0.9 * navigation::kMaxWaypointM;  // the pose wanders over hours
    for (std::size_t i = 0; i < count; ++i) {
      x = std::clamp(x + random_.uniform(-kMissionReachM, kMissionReachM), -limit, limit);
      y = std::clamp(y + random_.uniform(-kMissionReachM, kMissionReachM), -limit, limit);
      m.waypoints.push_back({x, y});
    }
  }
  if (random_.chance(1.0 / 3.0)) m.settle_s = random_.uniform(1.0, 10.0);
  return m;
}

void OperatorScript::start_activity(std::int64_t time_us, const driver::DriverStatus& status) {
  if (activity_ == Activity::kHandOver) use_gamepad_ = !use_gamepad_;  // the new console drives
  double total = 0.0;
  for (double w : kWeights) total += w;
  double pick = random_.uniform(0.0, total);
  std::size_t a = 0;
  while (a + 1 < kActivityCount && pick >= kWeights[a]) pick -= kWeights[a++];
  activity_ = static_cast<Activity>(a);
  ++stats_.activities[a];
  const OperatorParams& o = params_->operator_input;
  const JointParams& j = params_->joints;
  targets_ = {};
  double seconds = random_.uniform(2.0, 15.0);
  auto fraction = [this] { return random_.uniform(-1.0, 1.0); };
  switch (activity_) {
    case Activity::kDrive: targets_.v1_radps = fraction() * o.max_drive_speed_radps; break;
    case Activity::kSpin: targets_.v2_radps = fraction() * o.max_spin_speed_radps; break;
    case Activity::kTrench: targets_.v4_radps = fraction() * o.max_trench_speed_radps; break;
    case Activity::kDriveAndSpin:
      targets_.v1_radps = fraction() * o.max_drive_speed_radps;
      targets_.v2_radps = fraction() * o.max_spin_speed_radps;
      break;
    case Activity::kJoints:
      // What the joint buttons give: ± the button speed, or nothing, per joint.
      targets_.v6_radps = static_cast<double>(random_.below(3)) - 1.0;
      targets_.v7_radps = static_cast<double>(random_.below(3)) - 1.0;
      targets_.v6_radps *= o.joint_button_speed_radps;
      targets_.v7_radps *= o.joint_button_speed_radps;
      seconds = random_.uniform(1.0, 8.0);
      break;
    case Activity::kJointTargets:
      targets_.front_joint_target_rad = random_.uniform(j.front_min_rad, j.front_max_rad);
      targets_.rear_joint_target_rad = random_.uniform(j.rear_min_rad, j.rear_max_rad);
      seconds = random_.uniform(3.0, 12.0);
      break;
    case Activity::kGait: {
      targets_.gait = kGaits[random_.below(kGaits.size())];
      const double speed = random_.uniform(0.3, 1.0);
      targets_.gait_speed = random_.chance(0.7) ? speed : -speed;
      seconds = random_.uniform(5.0, 30.0);
      break;
    }
    case Activity::kStop: seconds = random_.uniform(1.0, 4.0); break;
    case Activity::kHandOver:
      ++stats_.hand_overs;
      seconds = random_.uniform(0.2, 1.5);  // until the other console's first message
      break;
    case Activity::kVelocity:
      // Inside the limits check_velocity holds them to (the largest |v| and |ω| included).
      velocity_ = {fraction() * navigation::max_velocity_mps(*params_),
                   fraction() * navigation::max_yaw_rate_radps(*params_)};
      break;
    case Activity::kMission:
      mission_ = random_mission(status);
      seconds = random_.uniform(10.0, 60.0);  // often ended early by what the operator does next
      break;
    case Activity::kSilence: {
      const double timeout_s = params_->safety.operator_timeout_s;
      const bool long_one = random_.chance(0.5);
      seconds = long_one ? random_.uniform(timeout_s + 0.05, 6.0)
                         : random_.uniform(0.05, timeout_s - 0.05);
      ++(long_one ? stats_.long_silences : stats_.short_silences);
      break;
    }
  }
  activity_start_us_ = time_us;
  activity_end_us_ = time_us + std::llround(seconds * 1e6);
}

driver::OperatorInput OperatorScript::gamepad_command(bool first_cycle) const {
  const OperatorParams& o = params_->operator_input;
  mobility::GamepadState pad;
  pad.axes[mobility::kLeftStickY] = -targets_.v1_radps / o.max_drive_speed_radps;
  pad.axes[mobility::kLeftStickX] = -targets_.v2_radps / o.max_spin_speed_radps;
  pad.axes[mobility::kRightStickX] = targets_.v4_radps / o.max_trench_speed_radps;
  pad.axes[mobility::kRightStickY] = -targets_.gait_speed;
  pad.buttons[mobility::kLeftBumper] = targets_.v6_radps > 0.0;    // contract front
  pad.buttons[mobility::kLeftTrigger] = targets_.v6_radps < 0.0;   // extend front
  pad.buttons[mobility::kRightTrigger] = targets_.v7_radps > 0.0;  // extend rear
  pad.buttons[mobility::kRightBumper] = targets_.v7_radps < 0.0;   // contract rear
  if (first_cycle) {  // a gait is chosen (or left, with B) by a press
    const auto it = std::find(kGaits.begin(), kGaits.end(), targets_.gait);
    const std::size_t button = it == kGaits.end()
                                   ? std::size_t{mobility::kButtonRight}
                                   : kGaitButtons[static_cast<std::size_t>(it - kGaits.begin())];
    pad.buttons[button] = true;
  }
  driver::OperatorInput input;
  input.gamepad = pad;
  return input;
}

driver::OperatorInput OperatorScript::command(bool first_cycle) {
  driver::OperatorInput input;
  if (activity_ == Activity::kVelocity) {
    input.velocity = velocity_;  // either console: the stick's velocity mode or the form's
  } else if (activity_ == Activity::kMission) {
    // The mission once, then what the console sends while it runs and the pad rests.
    if (first_cycle) {
      input.mission = mission_;
    } else {
      input.heartbeat = true;
      ++stats_.heartbeats;
    }
  } else if (use_gamepad_) {
    input = gamepad_command(first_cycle);
  } else {
    input.targets = targets_;
  }
  return input;
}

const driver::OperatorInput* OperatorScript::next(std::int64_t time_us,
                                                  const driver::DriverStatus& status) {
  if (time_us >= activity_end_us_) start_activity(time_us, status);
  const bool first_cycle = time_us == activity_start_us_;
  if (!status.faults.empty() && !clear_at_us_) {
    clear_at_us_ = time_us + std::llround(random_.uniform(0.5, 3.0) * 1e6);
  }
  if (activity_ == Activity::kSilence) return nullptr;
  if (activity_ == Activity::kHandOver || activity_ == Activity::kStop) {
    // The console's stop (on a hand-over the link stops the rover itself), then nothing while
    // control changes hands, or the operator's sticks at rest.
    if (first_cycle) {
      input_ = {};
      input_.stop = true;
    } else if (activity_ == Activity::kHandOver) {
      return nullptr;
    } else {
      input_ = command(false);
    }
  } else {
    if (!first_cycle && random_.chance(kDroppedMessage)) return nullptr;
    input_ = command(first_cycle);
  }
  if (clear_at_us_ && time_us >= *clear_at_us_) {
    input_.clear_faults = true;
    ++stats_.fault_clears;
    clear_at_us_.reset();
  }
  ++stats_.commands;
  return &input_;
}

}  // namespace marsokhod::runner
