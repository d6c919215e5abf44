// The three constants of Lemma 4.15 and its discretisation (4.12)/(4.13).
//
//   rate_per_s  μ [1/s]   how fast v follows the control c in (4.9): ∂t v = μ(c − v)
//   max_speed   C [u/s]   the bound |c| ≤ C, hence |v| ≤ C (u: rad for the joints and wheels)
//   period_s    h [s]     one communication cycle (0.0156 s at 64 Hz)
//
// All three must be finite and > 0. Every law validates its ControlParams on entry (three
// comparisons) rather than trusting the caller.
#pragma once

#include "core/params.hpp"

namespace marsokhod::control {

struct ControlParams {
  double rate_per_s = 0.0;  // μ
  double max_speed = 0.0;   // C
  double period_s = 0.0;    // h
};

// Throws std::invalid_argument naming the field unless μ, C and h are finite and > 0.
void validate(const ControlParams& params);

// The joint controller of Figure 4.11: μ = joints.control_rate_per_s,
// C = joints.control_speed_fraction · motors.max_no_load_speed_radps (w/2 = 1.4135 rad/s),
// h = cycle.period_s. Validated.
ControlParams joint_control_params(const Params& params);

}  // namespace marsokhod::control
