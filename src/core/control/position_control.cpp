#include "core/control/position_control.hpp"

#include <algorithm>
#include <cmath>

#include "core/checks/checks.hpp"

namespace marsokhod::control {

namespace {

// v_d is kept strictly inside (−C, C): see the header.
constexpr double kTargetSpeedFraction = 1.0 - 1e-9;
constexpr int kMaxBisections = 200;
// |p_d − p_T| below this fraction of |p| + |p_d| + C/μ counts as on Γ: thousands of rounding
// errors of p_T, yet far below any physical position (about 1e-11 rad for the joints).
constexpr double kCurveTolerance = 1e-12;

// One validated problem: params, step coefficients and the clamped target.
struct Problem {
  double max_speed;
  double rate_per_s;
  StepCoefficients coefficients;
  MotionState target;
};

Problem make_problem(const MotionState& state, const MotionState& target,
                     const ControlParams& params, std::string_view law) {
  const StepCoefficients coefficients = step_coefficients(params);
  checks::law::require_finite(state.position, law, "state.position");
  checks::law::require_finite(state.velocity, law, "state.velocity");
  checks::law::require_finite(target.position, law, "target.position");
  checks::law::require_finite(target.velocity, law, "target.velocity");
  const double limit = kTargetSpeedFraction * params.max_speed;
  return {params.max_speed, params.rate_per_s, coefficients,
          {target.position, std::clamp(target.velocity, -limit, limit)}};
}

double terminal_position(const MotionState& state, const Problem& problem) {
  const double speed = problem.max_speed;
  const double velocity = std::clamp(state.velocity, -speed, speed);
  const double target_velocity = problem.target.velocity;
  if (velocity == target_velocity) {
    return state.position;
  }
  const double control = velocity < target_velocity ? speed : -speed;
  // log((c − v)/(c − v_d)) = log1p((v_d − v)/(c − v_d)): exact near v = v_d.
  const double log_ratio = std::log1p((target_velocity - velocity) / (control - target_velocity));
  return state.position + (velocity - target_velocity + control * log_ratio) / problem.rate_per_s;
}

// p_d − p_T: > 0 asks for +C, < 0 for −C, 0 on the switching curve Γ.
double switching_gap(const MotionState& state, const Problem& problem) {
  return problem.target.position - terminal_position(state, problem);
}

// +1, −1, or 0 when the state is on Γ up to rounding. The tolerance matters: for v_d ≠ 0, on
// the arc of Γ where v lies between 0 and v_d, −C makes p_T grow, so a rounding-sized negative
// gap would send a state that has landed on Γ off with −C into a long detour.
int switching_side(const MotionState& state, const Problem& problem) {
  const double gap = switching_gap(state, problem);
  const double scale = std::abs(state.position) + std::abs(problem.target.position) +
                       problem.max_speed / problem.rate_per_s;
  if (gap > kCurveTolerance * scale) {
    return 1;
  }
  return gap < -kCurveTolerance * scale ? -1 : 0;
}

// Rule 2: ±C toward Γ, or the c nearest to it whose next state does not cross Γ.
double landing_control(const MotionState& state, const Problem& problem) {
  const double speed = problem.max_speed;
  const int side = switching_side(state, problem);
  const double velocity = std::clamp(state.velocity, -speed, speed);
  if (side == 0 && velocity == problem.target.velocity) {
    return problem.target.velocity;  // at the target up to rounding
  }
  // Off Γ: toward it. On Γ: along its arc into the target.
  double toward = velocity < problem.target.velocity ? speed : -speed;
  if (side != 0) {
    toward = side > 0 ? speed : -speed;
  }
  const int wrong_side = toward > 0.0 ? -1 : 1;
  const auto crosses = [&](double control) {
    return switching_side(step(state, control, problem.coefficients), problem) == wrong_side;
  };
  if (!crosses(toward)) {
    return toward;
  }
  if (crosses(-toward)) {  // Γ is passed whatever c: end nearer to it
    const auto distance = [&](double control) {
      return std::abs(switching_gap(step(state, control, problem.coefficients), problem));
    };
    return distance(-toward) < distance(toward) ? -toward : toward;
  }
  double keep = -toward;
  double cross = toward;
  for (int i = 0; i < kMaxBisections; ++i) {
    const double middle = 0.5 * (keep + cross);
    if (middle == keep || middle == cross) {
      break;
    }
    (crosses(middle) ? cross : keep) = middle;
  }
  return keep;
}

}  // namespace

double position_when_velocity_reached(const MotionState& state, double target_velocity,
                                      const ControlParams& params) {
  const Problem problem = make_problem(state, {0.0, target_velocity}, params,
                                       "position_when_velocity_reached (Lemma 4.15)");
  return terminal_position(state, problem);
}

double bang_bang_position_velocity_control(const MotionState& state, const MotionState& target,
                                           const ControlParams& params) {
  const Problem problem =
      make_problem(state, target, params, "bang_bang_position_velocity_control (4.15)");
  const double gap = switching_gap(state, problem);
  return gap > 0.0 ? params.max_speed : (gap < 0.0 ? -params.max_speed : 0.0);
}

double position_velocity_control(const MotionState& state, const MotionState& target,
                                 const ControlParams& params) {
  const Problem problem = make_problem(state, target, params, "position_velocity_control (4.15)");
  if (state.position == problem.target.position && state.velocity == problem.target.velocity) {
    return problem.target.velocity;
  }
  // Rule 1: the two-period exact solution, when both its controls fit |c| ≤ C.
  if (const auto controls =
          two_step_controls(state, problem.target, problem.max_speed, problem.coefficients)) {
    return controls->first;
  }
  return landing_control(state, problem);
}

}  // namespace marsokhod::control
