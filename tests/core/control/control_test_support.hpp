// Test helpers for the control layer: the parameter sets of Figure 4.10 and Procedure 4.17,
// reaching times read off a trajectory, the least time of one-switch bang-bang controls in
// continuous time (the reference for Lemma 4.15), and a check for std::invalid_argument.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <initializer_list>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "../../support/invalid_argument.hpp"
#include "core/control/control_params.hpp"
#include "core/control/motion_model.hpp"

namespace marsokhod::control::testing {

using test_support::kNaN;
inline constexpr double kInfinity = test_support::kInf;

// Figure 4.10: μ = 0.1 /s, C = 1, and the thesis' cycle h = 0.0156 s (64 Hz).
inline ControlParams figure_4_10_params() { return {0.1, 1.0, 0.0156}; }

// Number of whole periods that cover t_s seconds.
inline std::size_t steps_for(double t_s, const ControlParams& params) {
  return static_cast<std::size_t>(std::ceil(t_s / params.period_s));
}

// The first k with |p^k − p_d| ≤ position_tolerance and |v^k − v_d| ≤ velocity_tolerance.
inline std::optional<std::size_t> first_reach(const Trajectory& trajectory,
                                              const MotionState& target,
                                              double position_tolerance,
                                              double velocity_tolerance) {
  for (std::size_t k = 0; k < trajectory.states.size(); ++k) {
    const MotionState& state = trajectory.states[k];
    if (std::abs(state.position - target.position) <= position_tolerance &&
        std::abs(state.velocity - target.velocity) <= velocity_tolerance) {
      return k;
    }
  }
  return std::nullopt;
}

// The continuous-time control "s·C for t1 seconds, then C·sgn(v_d − v) until v = v_d": where
// it ends, and when. Built from the closed form (4.10)/(4.11) only.
struct OneSwitchEnd {
  double position;
  double time_s;
};
inline OneSwitchEnd one_switch_end(const MotionState& start, const MotionState& target,
                                   double rate_per_s, double first_control, double first_s) {
  const MotionState middle = closed_form(start, first_control, rate_per_s, first_s);
  if (middle.velocity == target.velocity) {
    return {middle.position, first_s};
  }
  const double speed = std::abs(first_control);
  const double last = middle.velocity < target.velocity ? speed : -speed;
  const double last_s =
      std::log((last - middle.velocity) / (last - target.velocity)) / rate_per_s;
  return {closed_form(middle, last, rate_per_s, last_s).position, first_s + last_s};
}

// The least time to (v_d, p_d) over the one-switch controls above (s = ±1; t1 = 0 is the
// constant-sign control): scan t1 on a grid of grid_s up to horizon_s for sign changes of the
// end position error, refine each by bisection, keep the fastest. These are the candidates of
// Lemma 4.15, found without its formula for p_T. Infinity if none reaches the target.
inline double best_one_switch_time(const MotionState& start, const MotionState& target,
                                   double rate_per_s, double max_speed, double grid_s,
                                   double horizon_s) {
  double best = kInfinity;
  const auto count = static_cast<std::size_t>(horizon_s / grid_s);
  for (const double first_control : {-max_speed, max_speed}) {
    const auto error = [&](double first_s) {
      return one_switch_end(start, target, rate_per_s, first_control, first_s).position -
             target.position;
    };
    double previous = error(0.0);
    if (previous == 0.0) {
      best = std::min(best, one_switch_end(start, target, rate_per_s, first_control, 0.0).time_s);
    }
    for (std::size_t i = 1; i <= count; ++i) {
      double low = static_cast<double>(i - 1) * grid_s;
      double high = static_cast<double>(i) * grid_s;
      const double current = error(high);
      if ((previous < 0.0) != (current < 0.0)) {
        const bool low_negative = previous < 0.0;
        for (int n = 0; n < 100; ++n) {
          const double middle = 0.5 * (low + high);
          ((error(middle) < 0.0) == low_negative ? low : high) = middle;
        }
        best = std::min(best,
                        one_switch_end(start, target, rate_per_s, first_control, high).time_s);
      }
      previous = current;
    }
  }
  return best;
}

using test_support::expect_invalid_argument;

}  // namespace marsokhod::control::testing
