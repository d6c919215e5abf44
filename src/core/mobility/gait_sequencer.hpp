// Runs one wheel-walking gait (gait_table.hpp) cycle by cycle: joint targets reached with (4.15),
// the next state once both joints are there and stopped, ρf and ρr for (5.1)/(5.2).
//
// Per cycle, with the gait speed s ∈ [−1, 1] (the right stick, Remark 5.7):
// - The gait runs through the segment (from, to) of its cycle: s > 0 approaches `to`, s < 0
//   approaches `from` (the cycle backward: the same transition undone). A state is reached when
//   both joints are within JointParams::target_tolerance_rad (0.05) of its targets and
//   |w| ≤ kStoppedSpeedRadps (0.02 rad/s, about 6 encoder counts per 64 Hz cycle), w the measured
//   joint velocity when given (else the velocity state: the commanded ŵ can stay ≈ 0.04 rad/s
//   while the motor stands in its dead zone, which would never count as stopped); then the
//   segment moves one state on in the direction of s. At most one state per cycle.
// - The joint controls: (4.15) toward (v_d, p_d) = (0, target) with μ = control_rate_per_s and
//   C = |s|·max_joint_speed_fraction·w, then clipped by (4.16)'s bound terms at the full
//   C = max_joint_speed_fraction·w. The clip keeps the joints inside their bounds even when |s|
//   drops while a joint moves faster than the new C could brake.
// - The bounds are (5.3) intersected with the behaviours' bounds of this cycle when given
//   (GaitInput::front_bounds, rear_bounds: the slant response (6.4), chapter 6.2's summation).
//   Every target is clipped into them, so a stroke ends at γ(σ) instead of beyond it and the
//   state is still reached; a joint outside them (a held one, or one the slope's bound moved
//   past) is pulled back inside by (4.16)'s bound terms at the full C. Where a bound lies beyond
//   the (5.3) stroke's end (γ(σ) > E), the bound wins: the target is the bound.
// - A transition the bounds leave no room (neither joint's clipped target differs from the state
//   just reached by more than target_tolerance_rad) is not started: the gait holds at the state
//   it reached (output.held_by_bounds) and goes on by itself once the bounds widen again.
//   Advancing would run through states without moving a joint, one per cycle.
// - s = 0 holds: no state change, and (4.14) brings both joints to rest (v_d = 0, full C, same
//   clip). The targets stay.
// - ρf, ρr follow the rule of the segment's `to` state in both directions (running a transition
//   backward undoes it with the same axle placement); the ε-formula uses the measured w6, w7,
//   and on a slope (input.uphill ≠ 0) takes the joints' mismatch uphill (axle_placement.hpp).
// - The driving intent ϱ (Remark 5.5) is latched when the gait starts and re-read at each state
//   change: backward mirrors the table (gait_table.hpp). Held joints keep the (5.3)-clamped
//   position measured then, as far as the behaviours' bounds of each cycle allow.
// - Selecting a different gait restarts at state 0 (segment (last, 0)); Gait::kNone stops the
//   sequencer (output.active = false, everything else zero).
// Every target lies in (5.3). Inputs are measured values; time enters only as the period h.
#pragma once

#include <cstddef>
#include <optional>
#include <utility>

#include "core/control/control_params.hpp"
#include "core/control/motion_model.hpp"
#include "core/mobility/axle_placement.hpp"
#include "core/mobility/gait_table.hpp"
#include "core/mobility/lever_geometry.hpp"
#include "core/params.hpp"

namespace marsokhod::mobility {

struct GaitInput {
  Gait gait = Gait::kNone;
  double gait_speed = 0.0;                         // s ∈ [−1, 1]
  DrivingIntent intent = DrivingIntent::kForward;  // ϱ
  // p6, p7 measured [rad]; the velocity is the joint's velocity state of (4.13) [rad/s]: the
  // measured one on an ideal joint, the last commanded ŵ on a joint with backlash (whose
  // measured velocity is 0 while the shaft crosses the gap, which would stall the law).
  control::MotionState front_joint;
  control::MotionState rear_joint;
  double period_s = 0.0;                           // h
  // The measured w6, w7 for the ε-formula of chapter 5.3 (docs/design.md: from the measured joint
  // velocities) and for "stopped"; without them the velocity states above are used.
  std::optional<double> front_measured_radps{};
  std::optional<double> rear_measured_radps{};
  // The behaviours' joint bounds of this cycle, e.g. (6.4)'s slant bounds with the driver's
  // backlash margin; each within (5.3) and min ≤ max. None: (5.3) alone.
  std::optional<JointBounds> front_bounds{};
  std::optional<JointBounds> rear_bounds{};
  // On a slope +1 when forward is uphill, −1 when backward is: the ε-formula's states then take
  // the joints' mismatch uphill (uphill_axle_factors). 0: the printed formula.
  double uphill = 0.0;
};

struct GaitOutput {
  bool active = false;
  std::size_t state_index = 0;       // the state being approached (or held at s = 0)
  double front_target_rad = 0.0;     // p6ᵈ
  double rear_target_rad = 0.0;      // p7ᵈ
  double front_control_radps = 0.0;  // c6 of (4.15)
  double rear_control_radps = 0.0;   // c7
  // v6, v7 for (5.4): the velocity (4.13) reaches after one period under c from the measured
  // state, i.e. the continuous ŵ6(t), ŵ7(t) of (4.11) that chapter 4.4 assigns to the motor.
  double front_command_radps = 0.0;
  double rear_command_radps = 0.0;
  AxleFactors factors;  // ρf, ρr
  // The next transition has no room inside the bounds: the gait holds at the reached state.
  bool held_by_bounds = false;
};

class GaitSequencer {
 public:
  static constexpr double kStoppedSpeedRadps = 0.02;

  // Validates the parameters (std::invalid_argument naming the field).
  GaitSequencer(const GeometryParams& geometry, const JointParams& joints, const GaitParams& gait,
                const MotorParams& motors);

  // One cycle. Throws std::invalid_argument naming the input if a number is not finite, |s| > 1
  // or h ≤ 0.
  GaitOutput update(const GaitInput& input);

  Gait gait() const { return gait_; }

 private:
  void start(const GaitInput& input);
  void latch_held_positions(const GaitInput& input);
  // A joint's bounds this cycle: (5.3) ∩ the behaviours' bounds (the behaviours' when disjoint).
  JointBounds effective_bounds(const JointBounds& own, const std::optional<JointBounds>& given) const;
  // The targets (p6ᵈ, p7ᵈ) of a state, clipped into the bounds of this cycle.
  std::pair<double, double> targets(std::size_t index, const GaitInput& input) const;
  bool reached(std::size_t index, const GaitInput& input) const;
  bool transition_has_room(bool forward, const GaitInput& input) const;
  void advance(bool forward, DrivingIntent intent, const GaitInput& input);
  AxleFactors segment_factors(const GaitInput& input) const;
  double joint_control(const control::MotionState& state, double target_rad, double gait_speed,
                       const JointBounds& bounds, const control::ControlParams& full) const;

  GeometryParams geometry_;
  JointParams joints_;
  JointBounds front_bounds_;
  JointBounds rear_bounds_;
  StrokePositions front_strokes_;
  StrokePositions rear_strokes_;
  double max_joint_speed_radps_ = 0.0;  // C at |s| = 1

  Gait gait_ = Gait::kNone;
  DrivingIntent intent_ = DrivingIntent::kForward;
  std::size_t from_ = 0;
  std::size_t to_ = 0;
  bool forward_ = true;  // the direction of the last s ≠ 0
  double held_front_rad_ = 0.0;
  double held_rear_rad_ = 0.0;
};

}  // namespace marsokhod::mobility
