// How a joint motor (6, 7) engages its joint through the backlash gap and the joint's lock.
//
// The motor shaft p̄ turns on the speed–torque line like a wheel motor. Between shaft and joint is
// the gap of Procedure 4.1: the shaft moves freely in [p, p + b] (docs/design.md's reading of (4.1)).
// The joint is not back-drivable (chapter 5.3: "a mechanism inside the joint prevents external
// load on the joint motor. The lock is suspended when the motor inside the joint spins and the
// backlash is overcome"). So a joint is in one of three modes:
//   locked         the joint holds its angle whatever the load; the shaft turns inside the gap
//   pushing up     the shaft, turning +, bears on the gap's upper end: p = p̄ − b, and the joint
//                  may move only + (a load stronger than the motor stalls it, never reverses it)
//   pushing down   likewise at the lower end: p = p̄, the joint moves only −
// The lock disengages when the shaft, commanded toward an end of the gap, reaches it; it engages
// again when the command stops or reverses. RoverPhysics turns each mode into MuJoCo constraints;
// this class is the decision, kept apart so that its rules can be tested without a simulator.
#pragma once

namespace marsokhod::sim {

enum class JointMode { kLocked, kPushingUp, kPushingDown };

class JointDrive {
 public:
  // Procedure 4.3: the joint starts locked at its angle with the shaft at the gap's lower end.
  JointDrive(double initial_joint_rad, double backlash_rad);

  // One decision per step from the measured shaft and joint angles and the commanded no-load
  // speed; returns true when the mode changed.
  bool update(double shaft_rad, double joint_rad, double no_load_speed_radps);

  JointMode mode() const { return mode_; }
  double backlash_rad() const { return backlash_rad_; }
  // Locked: the angle the lock holds; pushing: the furthest angle reached, which the joint may not
  // fall back behind.
  double held_angle_rad() const { return held_angle_rad_; }
  // Pushing: p = p̄ + this (−b at the upper end, 0 at the lower).
  double coupling_offset_rad() const {
    return mode_ == JointMode::kPushingUp ? -backlash_rad_ : 0.0;
  }

 private:
  double backlash_rad_;
  double held_angle_rad_;
  JointMode mode_ = JointMode::kLocked;
};

// (4.1) with docs/design.md's reading: P(p̄, p, b) = p̄ if p̄ < p; p if p ≤ p̄ ≤ p + b; p̄ − b if p̄ > p + b.
double backlash_position(double shaft_rad, double joint_rad, double backlash_rad);

}  // namespace marsokhod::sim
