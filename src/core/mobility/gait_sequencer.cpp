#include "core/mobility/gait_sequencer.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <tuple>
#include <stdexcept>
#include <string>

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
  if (input.uphill != 0.0 && input.uphill != 1.0 && input.uphill != -1.0) {
    throw std::invalid_argument(std::string(kWhere) + ": uphill must be 0, +1 or -1, got " +
                                std::to_string(input.uphill));
  }
  const auto check_bounds = [](const std::optional<JointBounds>& bounds, const char* min_name,
                               const char* max_name) {
    if (!bounds) return;
    checks::law::require_finite(bounds->min_rad, kWhere, min_name);
    checks::law::require_finite(bounds->max_rad, kWhere, max_name);
    if (bounds->min_rad > bounds->max_rad) {
      throw std::invalid_argument(std::string(kWhere) + ": " + min_name + " exceeds " + max_name +
                                  "; the behaviours' bounds must satisfy min ≤ max");
    }
  };
  check_bounds(input.front_bounds, "front_bounds.min_rad (p6_min)", "front_bounds.max_rad (p6_max)");
  check_bounds(input.rear_bounds, "rear_bounds.min_rad (p7_min)", "rear_bounds.max_rad (p7_max)");
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
  GaitOutput output;
  if (std::abs(input.gait_speed) * max_joint_speed_radps_ > 0.0) {
    forward_ = input.gait_speed > 0.0;
    if (reached(forward_ ? to_ : from_, input)) {
      if (transition_has_room(forward_, input)) {
        advance(forward_, input.intent, input);
      } else {
        output.held_by_bounds = true;
      }
    }
  }
  const std::size_t index = forward_ ? to_ : from_;
  output.active = true;
  output.state_index = index;
  std::tie(output.front_target_rad, output.rear_target_rad) = targets(index, input);
  const control::ControlParams full{joints_.control_rate_per_s, max_joint_speed_radps_,
                                    input.period_s};
  output.front_control_radps =
      joint_control(input.front_joint, output.front_target_rad, input.gait_speed,
                    effective_bounds(front_bounds_, input.front_bounds), full);
  output.rear_control_radps =
      joint_control(input.rear_joint, output.rear_target_rad, input.gait_speed,
                    effective_bounds(rear_bounds_, input.rear_bounds), full);
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

JointBounds GaitSequencer::effective_bounds(const JointBounds& own,
                                           const std::optional<JointBounds>& given) const {
  if (!given) return own;
  const JointBounds both{std::max(own.min_rad, given->min_rad), std::min(own.max_rad, given->max_rad)};
  // Disjoint only when a behaviour's bound lies in the stroke's backlash margin: the safety
  // bound wins.
  return both.min_rad <= both.max_rad ? both : *given;
}

std::pair<double, double> GaitSequencer::targets(std::size_t index, const GaitInput& input) const {
  const GaitState state = gait_state(gait_, index, intent_);
  return {effective_bounds(front_bounds_, input.front_bounds)
              .clamp(stroke_target_rad(state.front, front_strokes_, held_front_rad_)),
          effective_bounds(rear_bounds_, input.rear_bounds)
              .clamp(stroke_target_rad(state.rear, rear_strokes_, held_rear_rad_))};
}

bool GaitSequencer::transition_has_room(bool forward, const GaitInput& input) const {
  const std::size_t count = gait_states(gait_).size();
  const std::size_t next = forward ? (to_ + 1) % count : (from_ + count - 1) % count;
  // As advance() would start it: a new intent mirrors the table and re-latches the held joints.
  const bool relatch = input.intent != intent_;
  const GaitState state = gait_state(gait_, next, input.intent);
  const double held_front =
      relatch ? front_bounds_.clamp(input.front_joint.position) : held_front_rad_;
  const double held_rear = relatch ? rear_bounds_.clamp(input.rear_joint.position) : held_rear_rad_;
  const double front = effective_bounds(front_bounds_, input.front_bounds)
                           .clamp(stroke_target_rad(state.front, front_strokes_, held_front));
  const double rear = effective_bounds(rear_bounds_, input.rear_bounds)
                          .clamp(stroke_target_rad(state.rear, rear_strokes_, held_rear));
  // The joints stand at the reached state: a next state as near would be reached at once.
  return std::abs(front - input.front_joint.position) > joints_.target_tolerance_rad ||
         std::abs(rear - input.rear_joint.position) > joints_.target_tolerance_rad;
}

bool GaitSequencer::reached(std::size_t index, const GaitInput& input) const {
  // "Stopped" is the joint's measured velocity when there is one: the commanded ŵ of (4.13) can
  // stay a few hundredths of a rad/s off zero while the motor stands in its dead zone.
  const auto at = [&](const control::MotionState& joint, std::optional<double> measured_radps,
                      double target_rad) {
    return std::abs(joint.position - target_rad) <= joints_.target_tolerance_rad &&
           std::abs(measured_radps.value_or(joint.velocity)) <= kStoppedSpeedRadps;
  };
  const auto [front_target_rad, rear_target_rad] = targets(index, input);
  return at(input.front_joint, input.front_measured_radps, front_target_rad) &&
         at(input.rear_joint, input.rear_measured_radps, rear_target_rad);
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
  return input.uphill == 0.0 ? two_joint_axle_factors(rates, rule.epsilon)
                            : uphill_axle_factors(rates, rule.epsilon, input.uphill);
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
