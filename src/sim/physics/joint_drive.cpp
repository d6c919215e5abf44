#include "sim/physics/joint_drive.hpp"

#include <algorithm>

namespace marsokhod::sim {
namespace {

// The simulated gap's ends are soft constraints: a shaft resting on an end may sit this much
// short of it and still bears on it.
constexpr double kGapEndToleranceRad = 1e-6;
// A motor whose no-load speed has decayed below this is not pushing any more: with d = 0 the
// electrics' first-order lag only approaches 0, and without this floor the joint would stay
// coupled to a barely driven shaft and be back-driven by the wheels' forces.
constexpr double kPushingSpeedRadps = 1e-3;

}  // namespace

double backlash_position(double shaft_rad, double joint_rad, double backlash_rad) {
  if (shaft_rad < joint_rad) return shaft_rad;
  if (shaft_rad > joint_rad + backlash_rad) return shaft_rad - backlash_rad;
  return joint_rad;
}

JointDrive::JointDrive(double initial_joint_rad, double backlash_rad)
    : backlash_rad_(backlash_rad), held_angle_rad_(initial_joint_rad) {}

bool JointDrive::update(double shaft_rad, double joint_rad, double no_load_speed_radps) {
  const JointMode before = mode_;
  switch (mode_) {
    case JointMode::kPushingUp:
      if (no_load_speed_radps > kPushingSpeedRadps) {
        held_angle_rad_ = std::max(held_angle_rad_, joint_rad);
        return false;
      }
      break;
    case JointMode::kPushingDown:
      if (no_load_speed_radps < -kPushingSpeedRadps) {
        held_angle_rad_ = std::min(held_angle_rad_, joint_rad);
        return false;
      }
      break;
    case JointMode::kLocked:
      break;
  }
  // Locked, or the command stopped or reversed: engage the lock where the joint is, unless the
  // shaft is already bearing on the end it is commanded toward.
  if (mode_ != JointMode::kLocked) held_angle_rad_ = joint_rad;
  mode_ = JointMode::kLocked;
  // The gap is measured from the lock's angle, where the shaft's stops are: the (soft) lock lets
  // the joint itself creep a fraction of a milliradian under load, and a gap measured from the
  // joint could then never close.
  const double gap_rad = shaft_rad - held_angle_rad_;
  if (no_load_speed_radps > kPushingSpeedRadps && gap_rad >= backlash_rad_ - kGapEndToleranceRad) {
    mode_ = JointMode::kPushingUp;
  } else if (no_load_speed_radps < -kPushingSpeedRadps && gap_rad <= kGapEndToleranceRad) {
    mode_ = JointMode::kPushingDown;
  }
  if (mode_ != JointMode::kLocked) held_angle_rad_ = joint_rad;
  return mode_ != before;
}

}  // namespace marsokhod::sim
