#include "core/mobility/gait_sequencer.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "core/control/bounded_velocity_control.hpp"
#include "core/checks/checks.hpp"
#include "core/control/position_control.hpp"
#include "core/control/velocity_control.hpp"

namespace marsokhod::mobility {
namespace {

constexpr std::string_view kWhere = "GaitSequencer::update";

void check_input(const GaitInput& input) {
  checks::law::require_bounded(input.gait_speed, 1.0, kWhere, "gait_speed (s, the right stick)");
  checks::law::require_finite(input.front_joint.position, kWhere, "front_joint.position (p6)");
  checks::law::require_finite(input.front_joint.velocity, kWhere, "front_joint.velocity (w6)");
  checks::law::require_finite(input.rear_joint.position, kWhere, "rear_joint.position (p7)");
  checks::law::require_finite(input.rear_joint.velocity, kWhere, "rear_joint.velocity (w7)");
  if (input.front_measured_radps) {
    checks::law::require_finite(*input.front_measured_radps, kWhere, "front_measured_radps (w6)");
  }
  if (input.rear_measured_radps) {
    checks::law::require_finite(*input.rear_measured_radps, kWhere, "rear_measured_radps (w7)");
  }
  checks::law::require_positive(input.period_s, kWhere, "period_s (h)");
}

}  // namespace

GaitSequencer::GaitSequencer(const GeometryParams& geometry, const JointParams& joints,
                             const GaitParams& gait, const MotorParams& motors)
    : geometry_(geometry),
      joints_(joints),
      front_bounds_(front_joint_bounds(joints)),
      rear_bounds_(rear_joint_bounds(joints)),
      front_strokes_(front_stroke_positions(geometry, gait, joints)),
      rear_strokes_(rear_stroke_positions(geometry, gait, joints)),
      max_joint_speed_radps_(gait.max_joint_speed_fraction * motors.max_no_load_speed_radps) {
  checks::law::require_positive(motors.max_no_load_speed_radps, "GaitSequencer",
                            "MotorParams::max_no_load_speed_radps (w, 2.827)");
}

GaitOutput GaitSequencer::update(const GaitInput& input) {
  check_input(input);
  if (input.gait == Gait::kNone) {
    gait_ = Gait::kNone;
    return {};
  }
  if (input.gait != gait_) {
    start(input);
  }
  if (std::abs(input.gait_speed) * max_joint_speed_radps_ > 0.0) {
    forward_ = input.gait_speed > 0.0;
    if (reached(forward_ ? to_ : from_, input)) {
      advance(forward_, input.intent, input);
    }
  }
  const std::size_t index = forward_ ? to_ : from_;
  const GaitState state = gait_state(gait_, index, intent_);
  GaitOutput output;
  output.active = true;
  output.state_index = index;
  output.front_target_rad = stroke_target_rad(state.front, front_strokes_, held_front_rad_);
  output.rear_target_rad = stroke_target_rad(state.rear, rear_strokes_, held_rear_rad_);
  const control::ControlParams full{joints_.control_rate_per_s, max_joint_speed_radps_,
                                    input.period_s};
  output.front_control_radps = joint_control(input.front_joint, output.front_target_rad,
                                             input.gait_speed, front_bounds_, full);
  output.rear_control_radps =
      joint_control(input.rear_joint, output.rear_target_rad, input.gait_speed, rear_bounds_, full);
  output.front_command_radps =
      control::step(input.front_joint, output.front_control_radps, full).velocity;
  output.rear_command_radps =
      control::step(input.rear_joint, output.rear_control_radps, full).velocity;
  output.factors = segment_factors(input);
  return output;
}

void GaitSequencer::start(const GaitInput& input) {
  gait_ = input.gait;
  intent_ = input.intent;
  from_ = gait_states(gait_).size() - 1;
  to_ = 0;
  forward_ = true;
  latch_held_positions(input);
}

void GaitSequencer::latch_held_positions(const GaitInput& input) {
  held_front_rad_ = front_bounds_.clamp(input.front_joint.position);
  held_rear_rad_ = rear_bounds_.clamp(input.rear_joint.position);
}

bool GaitSequencer::reached(std::size_t index, const GaitInput& input) const {
  const GaitState state = gait_state(gait_, index, intent_);
  // "Stopped" is the joint's measured velocity when there is one: the commanded ŵ of (4.13) can
  // stay a few hundredths of a rad/s off zero while the motor stands in its dead zone.
  const auto at = [&](const control::MotionState& joint, std::optional<double> measured_radps,
                      double target_rad) {
    return std::abs(joint.position - target_rad) <= joints_.target_tolerance_rad &&
           std::abs(measured_radps.value_or(joint.velocity)) <= kStoppedSpeedRadps;
  };
  return at(input.front_joint, input.front_measured_radps,
            stroke_target_rad(state.front, front_strokes_, held_front_rad_)) &&
         at(input.rear_joint, input.rear_measured_radps,
            stroke_target_rad(state.rear, rear_strokes_, held_rear_rad_));
}

void GaitSequencer::advance(bool forward, DrivingIntent intent, const GaitInput& input) {
  const std::size_t count = gait_states(gait_).size();
  if (forward) {
    from_ = to_;
    to_ = (to_ + 1) % count;
  } else {
    to_ = from_;
    from_ = (from_ + count - 1) % count;
  }
  if (intent != intent_) {
    intent_ = intent;
    latch_held_positions(input);
  }
}

AxleFactors GaitSequencer::segment_factors(const GaitInput& input) const {
  const AxleRule rule = gait_state(gait_, to_, intent_).rule;
  if (rule.kind == AxleRule::Kind::kFixed) {
    return rule.fixed;
  }
  const AxleDistanceRates rates =
      axle_distance_rates(input.front_joint.position, input.rear_joint.position,
                          input.front_measured_radps.value_or(input.front_joint.velocity),
                          input.rear_measured_radps.value_or(input.rear_joint.velocity), geometry_);
  return two_joint_axle_factors(rates, rule.epsilon);
}

double GaitSequencer::joint_control(const control::MotionState& state, double target_rad,
                                    double gait_speed, const JointBounds& bounds,
                                    const control::ControlParams& full) const {
  const control::ControlParams scaled{full.rate_per_s, std::abs(gait_speed) * full.max_speed,
                                      full.period_s};
  // s = 0 (or so small that |s|·C underflows) holds: come to rest with the full C.
  const double command = scaled.max_speed > 0.0
                             ? control::position_velocity_control(state, {target_rad, 0.0}, scaled)
                             : control::velocity_control(state.velocity, 0.0, full);
  const double lowest = control::lower_bound_control(state, bounds.min_rad, full);
  const double highest = control::upper_bound_control(state, bounds.max_rad, full);
  return std::min(std::max(lowest, command), highest);
}

}  // namespace marsokhod::mobility
