#include "core/control/motion_model.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace marsokhod::control {

namespace {

// 1 − e^(−x) without cancellation for small x.
double rise(double x) { return -std::expm1(-x); }

// x − 1 + e^(−x) = x²/2 − x³/6 + …, the factor of c/μ in (4.10)/(4.12). Direct evaluation
// loses about log10(2/x) digits to cancellation, so small x take the alternating series (its
// terms up to x^12 leave a remainder below 1e-20 relative for x < 0.1).
double ramp_deficit(double x) {
  if (x < 0.1) {
    double term = 0.5 * x * x;
    double sum = term;
    for (int n = 3; n <= 12; ++n) {
      term *= -x / n;
      sum += term;
    }
    return sum;
  }
  return x + std::expm1(-x);
}

}  // namespace

MotionState closed_form(const MotionState& initial, double control, double rate_per_s,
                        double t_s) {
  constexpr std::string_view kLaw = "closed_form (4.10)/(4.11)";
  checks::law::require_finite(initial.position, kLaw, "initial.position");
  checks::law::require_finite(initial.velocity, kLaw, "initial.velocity");
  checks::law::require_finite(control, kLaw, "control");
  checks::law::require_positive(rate_per_s, kLaw, "rate_per_s");
  checks::law::require_finite(t_s, kLaw, "t_s");
  if (t_s < 0.0) {
    throw std::invalid_argument("closed_form (4.10)/(4.11): t_s must be ≥ 0 (the model runs "
                                "forward from the initial state), got " + std::to_string(t_s));
  }
  const double x = t_s * rate_per_s;
  return {initial.position + (initial.velocity * rise(x) + control * ramp_deficit(x)) / rate_per_s,
          initial.velocity * std::exp(-x) + control * rise(x)};
}

StepCoefficients step_coefficients(const ControlParams& params) {
  validate(params);
  const double x = params.period_s * params.rate_per_s;
  return {std::exp(-x), rise(x), rise(x) / params.rate_per_s,
          ramp_deficit(x) / params.rate_per_s};
}

MotionState step(const MotionState& state, double control, const StepCoefficients& coefficients) {
  constexpr std::string_view kLaw = "step (4.12)/(4.13)";
  checks::law::require_finite(state.position, kLaw, "state.position");
  checks::law::require_finite(state.velocity, kLaw, "state.velocity");
  checks::law::require_finite(control, kLaw, "control");
  return {state.position + coefficients.position_per_velocity_s * state.velocity +
              coefficients.position_per_control_s * control,
          coefficients.velocity_decay * state.velocity + coefficients.control_gain * control};
}

MotionState step(const MotionState& state, double control, const ControlParams& params) {
  return step(state, control, step_coefficients(params));
}

// With v1 = e·v + g·c0, p1 = p + a·v + b·c0 and c1 = (v_d − e·v1)/g, the remaining condition
// p1 + a·v1 + b·c1 = p_d is linear in c0; its coefficient b·(1 − e) + a·g is > 0.
std::optional<TwoStepControls> two_step_controls(const MotionState& state,
                                                 const MotionState& target, double max_speed,
                                                 const StepCoefficients& coefficients) {
  constexpr std::string_view kLaw = "two_step_controls (4.12)/(4.13)";
  checks::law::require_finite(state.position, kLaw, "state.position");
  checks::law::require_finite(state.velocity, kLaw, "state.velocity");
  checks::law::require_finite(target.position, kLaw, "target.position");
  checks::law::require_finite(target.velocity, kLaw, "target.velocity");
  const double e = coefficients.velocity_decay;
  const double g = coefficients.control_gain;
  const double a = coefficients.position_per_velocity_s;
  const double b = coefficients.position_per_control_s;
  const double slope = a - b * e / g;  // ∂p2/∂v1 once c1 restores v_d
  const double first = (target.position - b * target.velocity / g - state.position -
                        a * state.velocity - slope * e * state.velocity) /
                       (b + slope * g);
  const double second = (target.velocity - e * (e * state.velocity + g * first)) / g;
  // Written so that a NaN (0/0 after an underflow, ∞ − ∞) fails the test.
  if (std::abs(first) <= max_speed && std::abs(second) <= max_speed) {
    return TwoStepControls{first, second};
  }
  return std::nullopt;
}

}  // namespace marsokhod::control
