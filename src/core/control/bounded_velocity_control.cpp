#include "core/control/bounded_velocity_control.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/checks/checks.hpp"
#include "core/control/velocity_control.hpp"

namespace marsokhod::control {

namespace {

constexpr int kMaxBisections = 200;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The highest position reached from `state` when braking with c = −C: the stop point when
// moving up, the position itself otherwise. Non-decreasing in v and p.
double highest_reach(const MotionState& state, double max_speed, double rate_per_s) {
  if (!(state.velocity > 0.0)) {
    return state.position;
  }
  // p_T of Lemma 4.15 with v_d = 0, c = −C: p + (v − C·log(1 + v/C))/μ ≥ p.
  const double stop =
      state.position +
      (state.velocity - max_speed * std::log1p(state.velocity / max_speed)) / rate_per_s;
  return std::max(state.position, stop);
}

// Unvalidated upper term: the largest c with highest_reach(next(c)) ≤ max_position, except at
// the very end, where the two-period exact stop at max_position is taken if it never passes it.
double upper_term(const MotionState& state, double max_position, const ControlParams& params,
                  const StepCoefficients& coefficients) {
  const double speed = params.max_speed;
  if (max_position == kInfinity) {
    return speed;
  }
  const auto fits = [&](double control) {
    return highest_reach(step(state, control, coefficients), speed, params.rate_per_s) <=
           max_position;
  };
  if (fits(speed)) {
    return speed;
  }
  if (!fits(-speed)) {
    return -speed;
  }
  const auto stop = two_step_controls(state, {max_position, 0.0}, speed, coefficients);
  if (stop && fits(stop->first)) {
    return stop->first;
  }
  double keep = -speed;
  double cross = speed;
  for (int i = 0; i < kMaxBisections; ++i) {
    const double middle = 0.5 * (keep + cross);
    if (middle == keep || middle == cross) {
      break;
    }
    (fits(middle) ? keep : cross) = middle;
  }
  return keep;
}

// The lower term is the upper term of the mirrored axis p → −p (the model is odd in (v, p, c)).
double lower_term(const MotionState& state, double min_position, const ControlParams& params,
                  const StepCoefficients& coefficients) {
  return -upper_term({-state.position, -state.velocity}, -min_position, params, coefficients);
}

void require_state(const MotionState& state, std::string_view law) {
  checks::law::require_finite(state.position, law, "state.position");
  checks::law::require_finite(state.velocity, law, "state.velocity");
}

void require_bounds(double min_position, double max_position, std::string_view law) {
  if (std::isnan(min_position) || std::isnan(max_position) || min_position == kInfinity ||
      max_position == -kInfinity || min_position > max_position) {
    std::ostringstream message;
    message << law << ": the position bounds must satisfy −∞ ≤ min_position ≤ max_position ≤ +∞ "
            << "(no NaN), got min_position = " << min_position
            << ", max_position = " << max_position
            << "; pass −∞/+∞ to switch a bound off";
    throw std::invalid_argument(message.str());
  }
}

}  // namespace

double upper_bound_control(const MotionState& state, double max_position,
                           const ControlParams& params) {
  constexpr std::string_view kLaw = "upper_bound_control (4.16)";
  const StepCoefficients coefficients = step_coefficients(params);
  require_state(state, kLaw);
  require_bounds(-kInfinity, max_position, kLaw);
  return upper_term(state, max_position, params, coefficients);
}

double lower_bound_control(const MotionState& state, double min_position,
                           const ControlParams& params) {
  constexpr std::string_view kLaw = "lower_bound_control (4.16)";
  const StepCoefficients coefficients = step_coefficients(params);
  require_state(state, kLaw);
  require_bounds(min_position, kInfinity, kLaw);
  return lower_term(state, min_position, params, coefficients);
}

double bounded_velocity_control(const MotionState& state, double target_velocity,
                                double min_position, double max_position,
                                const ControlParams& params) {
  constexpr std::string_view kLaw = "bounded_velocity_control (4.16)";
  const StepCoefficients coefficients = step_coefficients(params);
  require_state(state, kLaw);
  checks::law::require_finite(target_velocity, kLaw, "target_velocity");
  require_bounds(min_position, max_position, kLaw);
  const double lower = lower_term(state, min_position, params, coefficients);
  const double upper = upper_term(state, max_position, params, coefficients);
  return std::min(std::max(lower, velocity_control(state.velocity, target_velocity, params)),
                  upper);
}

}  // namespace marsokhod::control
