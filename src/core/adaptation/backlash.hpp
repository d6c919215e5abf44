// (4.1), (4.2) backlash: the position p and velocity w of a joint (or wheel) behind a gear with
// play b, from the position p̄ and velocity w̄ of its motor shaft (chapter 4.1, Example 4.2, as
// docs/design.md fixes the lost table). The shaft moves freely in [p, p + b]; pushing past either end
// drags the joint along:
//   P(p̄, p, b)  = p̄       if p̄ < p
//               = p       if p ≤ p̄ ≤ p + b
//               = p̄ − b   if p̄ > p + b
//   P⁺(p̄, p, b) = clip((p̄ − p)/b, 0, 1),   P⁻ = 1 − P⁺
//   b = 0:  P = p̄,  P⁺ = P⁻ = 1  (the wheels, Procedure 4.1's simplified backlash vector).
// P± is the fraction of the gap already crossed towards the end the shaft is turning to, so
// (4.2)'s velocity fades in across the gap instead of jumping when the gear engages.
#pragma once

#include <array>
#include <cstddef>

#include "core/params.hpp"

namespace marsokhod::adaptation {

// P of (4.1). Throws std::invalid_argument on a non-finite argument or backlash_rad < 0.
double backlash_position(double motor_position_rad, double joint_position_rad, double backlash_rad);

// P⁺: the share of a positive motor velocity that reaches the joint. Same checks.
double backlash_factor_positive(double motor_position_rad, double joint_position_rad,
                                double backlash_rad);

// P⁻ = 1 − P⁺ (1 when b = 0): the share of a negative motor velocity. Same checks.
double backlash_factor_negative(double motor_position_rad, double joint_position_rad,
                                double backlash_rad);

// (4.2) w̄ · P^(sgn w̄)(p̄, p, b). For w̄ = 0 the result is 0 (no factor is needed). Same checks.
double backlash_velocity(double motor_position_rad, double motor_velocity_radps,
                         double joint_position_rad, double backlash_rad);

// One motor's joint (or wheel) state under (4.1), (4.2).
class BacklashTracker {
 public:
  // Procedure 4.3 / Remark 3.1: the motor has been driven to the negative end of the gap, so
  // p⁰ = p̄⁰ (p = P(p, p, b)); the joint is at rest. Throws on a non-finite argument or b < 0.
  BacklashTracker(double backlash_rad, double initial_position_rad);

  // One cycle k → k + 1: p^(k+1) = P(p̄^k, p^k, b), w^(k+1) = w̄^k P^(sgn w̄^k)(p̄^k, p^k, b).
  // Throws on a non-finite argument and then leaves the state unchanged.
  void update(double motor_position_rad, double motor_velocity_radps);

  // Procedure 4.3 again (calibration mode): p = p̄ = position_rad, w = 0.
  void reset(double position_rad);

  double backlash_rad() const { return backlash_rad_; }
  double joint_position_rad() const { return joint_position_rad_; }      // p
  double joint_velocity_radps() const { return joint_velocity_radps_; }  // w

 private:
  double backlash_rad_;
  double joint_position_rad_;
  double joint_velocity_radps_ = 0.0;
};

// The eight trackers of the rover, in the motor order of (3.1); the wheels have b = 0, so their
// p and w equal the motor's.
class RoverBacklashTracker {
 public:
  // b = motors.backlash_rad, p⁰ = p̄⁰ = motors.initial_position_rad (Procedure 4.3).
  explicit RoverBacklashTracker(const MotorParams& motors);
  RoverBacklashTracker(const MotorVector& backlash_rad, const MotorVector& initial_position_rad);

  // (4.1), (4.2) for all eight motors. Throws std::invalid_argument naming the first non-finite
  // entry, before any tracker changes.
  void update(const MotorVector& motor_position_rad, const MotorVector& motor_velocity_radps);

  // Procedure 4.3 for all eight motors.
  void reset(const MotorVector& initial_position_rad);

  MotorVector joint_position_rad() const;
  MotorVector joint_velocity_radps() const;
  const BacklashTracker& motor(std::size_t index) const { return trackers_.at(index); }

 private:
  std::array<BacklashTracker, kMotorCount> trackers_;
};

}  // namespace marsokhod::adaptation
