// The model of Lemma 4.15 and its exact discretisation.
//
//   ∂t p = v                                                                       (4.8)
//   ∂t v = μ(c − v),   μ > 0, |c| ≤ C                                              (4.9)
//
// For a control c held constant from the state (v0, p0) at t = 0:
//   p(t) = p0 + v0/μ·(1 − e^(−tμ)) − c/μ·(1 − tμ − e^(−tμ))                        (4.10)
//   v(t) = v0·e^(−tμ) + c·(1 − e^(−tμ))                                             (4.11)
// and, holding c^k over one period h (zero-order hold, so exact for the model):
//   p^(k+1) = p^k + v^k/μ·(1 − e^(−hμ)) − c^k/μ·(1 − hμ − e^(−hμ))                  (4.12)
//   v^(k+1) = v^k·e^(−hμ) + c^k·(1 − e^(−hμ))                                        (4.13)
//
// Units: p in u, v and c in u/s, μ in 1/s, t and h in s (u = rad for the joints). v(t) is a
// convex combination of v0 and c, so |v0| ≤ C and |c| ≤ C keep |v| ≤ C. The coefficient
// 1 − hμ − e^(−hμ) is O((hμ)²) and is evaluated by a series for small hμ, so that (4.10) and
// (4.12) agree to rounding even at 64 Hz. Every function rejects a NaN or infinite input with
// std::invalid_argument.
#pragma once

#include <concepts>
#include <cstddef>
#include <optional>
#include <vector>

#include "core/control/control_params.hpp"
#include "core/checks/checks.hpp"

namespace marsokhod::control {

// One axis: position p [u] and velocity v [u/s]. Also used for a target state (p_d, v_d).
struct MotionState {
  double position = 0.0;
  double velocity = 0.0;
};

// (4.10)/(4.11): the state t_s ≥ 0 seconds after `initial` under the constant control c.
MotionState closed_form(const MotionState& initial, double control, double rate_per_s,
                        double t_s);

// The coefficients of (4.12)/(4.13) for one period:
//   v' = velocity_decay·v + control_gain·c
//   p' = p + position_per_velocity_s·v + position_per_control_s·c
struct StepCoefficients {
  double velocity_decay = 1.0;          // e^(−hμ)
  double control_gain = 0.0;            // 1 − e^(−hμ)
  double position_per_velocity_s = 0.0;  // (1 − e^(−hμ))/μ [s]
  double position_per_control_s = 0.0;   // (hμ − 1 + e^(−hμ))/μ ≥ 0 [s]
};

// Validates params and computes the coefficients of (4.12)/(4.13).
StepCoefficients step_coefficients(const ControlParams& params);

// (4.12)/(4.13): the state one period after `state` under the control c (not clipped: the model
// itself allows any finite c; the laws keep |c| ≤ C).
MotionState step(const MotionState& state, double control, const StepCoefficients& coefficients);
MotionState step(const MotionState& state, double control, const ControlParams& params);

// The unique pair (c^k, c^(k+1)) that takes `state` exactly to `target` in two periods of
// (4.12)/(4.13) (the model is controllable in two steps), if both fit |c| ≤ max_speed;
// std::nullopt otherwise, also when extreme inputs overflow the arithmetic.
struct TwoStepControls {
  double first = 0.0;
  double second = 0.0;
};
std::optional<TwoStepControls> two_step_controls(const MotionState& state,
                                                 const MotionState& target, double max_speed,
                                                 const StepCoefficients& coefficients);

// A run of the model: states[k] for k = 0..n, controls[k] applied from states[k] to states[k+1].
struct Trajectory {
  std::vector<MotionState> states;
  std::vector<double> controls;
};

// Applies (4.12)/(4.13) for `steps` periods with c^k = law(state^k). Throws
// std::invalid_argument if the law returns a NaN, an infinity or |c| > C: the model of Lemma
// 4.15 assumes |c| ≤ C, and a test must not pass because the model silently clipped a control.
template <typename Law>
  requires std::invocable<Law&, const MotionState&>
Trajectory simulate(const MotionState& initial, const ControlParams& params, std::size_t steps,
                    Law&& law) {
  const StepCoefficients coefficients = step_coefficients(params);
  checks::law::require_finite(initial.position, "simulate", "initial.position");
  checks::law::require_finite(initial.velocity, "simulate", "initial.velocity");
  Trajectory trajectory;
  trajectory.states.reserve(steps + 1);
  trajectory.controls.reserve(steps);
  trajectory.states.push_back(initial);
  for (std::size_t k = 0; k < steps; ++k) {
    const double control = static_cast<double>(law(trajectory.states.back()));
    checks::law::require_bounded(control, params.max_speed, "simulate",
                                 "the control c returned by the law");
    trajectory.controls.push_back(control);
    trajectory.states.push_back(step(trajectory.states.back(), control, coefficients));
  }
  return trajectory;
}

}  // namespace marsokhod::control
