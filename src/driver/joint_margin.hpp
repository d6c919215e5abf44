// The joint bounds the driver steers by: (5.3) less what the driver cannot know of a unit's
// backlash gap.
//
// The driver sees the joints only through their motors' shafts p̄ and the backlash model
// (4.1)/(4.2) with the configured gap b. Procedure 4.3 (startup.hpp) ends with each shaft
// resting on the negative end of its gap, engaged with its joint, and sets p = p̄ there. From
// then on:
// - pushing a joint in the negative direction, the shaft drags it at the gap's negative end:
//   the joint is the shaft, p = p̄, whatever the unit's true gap b_t;
// - pushing it in the positive direction, the shaft drags it at the positive end: the joint is
//   p̄ − b_t, the driver's p = p̄ − b. The true joint lies b − b_t above the driver's p.
// A unit's gap differs from the configured one by up to `backlash_uncertainty`·b (a drawn unit
// of the simulator: 6–15 %; a real rover: what Procedure 4.1 left uncertain), so a joint driven
// to its positive bound may pass it by up to that much. The driver therefore keeps its own
// estimate that far inside the positive bounds — but only as far as the shaft has crossed its gap
// toward the positive end: the margin is backlash_uncertainty·b·P⁺(p̄, p, b) of (4.2) (0 with
// the shaft at the negative end, where the estimate is exact, as after Procedure 4.3; the full
// 0.0078 and 0.0375 rad with the thesis' 3° and 14° gaps while the shaft pushes the joint). A
// joint resting at its positive bound after Procedure 4.3 (p6 = −1.2121) is thus not moved.
// The negative bounds need no margin. Targets near a positive bound (the gaits' strokes) are
// planned inside the full margin (joint_bounds_with_backlash_margin), where the joint ends up
// after a positive push.
#pragma once

#include "core/params.hpp"

namespace marsokhod::driver {

// (5.3) with the positive bounds moved in by the full margin. Throws std::invalid_argument when
// the margin leaves a joint no range (max ≤ min).
JointParams joint_bounds_with_backlash_margin(const JointParams& joints, const MotorParams& motors);

// The margin [rad] for one joint now: uncertainty·b·P⁺(p̄, p, b).
double positive_bound_margin_rad(double backlash_uncertainty, double backlash_rad,
                                 double shaft_position_rad, double joint_position_rad);

}  // namespace marsokhod::driver

namespace marsokhod::driver {

// The dead man's run-on. The driver may die with the computer after any cycle (a brown-out);
// µi then keeps the duty of its last request until µ8's dead man's switch sets pwm = 0, 0.2621·dog
// s after the last 0x80 (chapter 3.3), and the motor needs its lag to stop after that. The joint
// meanwhile runs on at the speed its motor has at that duty under the load it meets: v + l, with
// v the commanded no-load velocity and l = w̄ − ν the shaft's load of (4.4) (positive for a unit
// faster than the model or a load that pulls the joint along; negative for a loaded or stalled
// motor, which runs on slower or not at all; the shaft's, not the joint's, so that a shaft
// crossing its gap counts at its own speed). It runs for about T_run = 0.262144·dog s + the
// joint's dead time (motion_controller.cpp). So a joint command toward a bound is limited to
// what stops there:
//   v ≤ (p_max − p)/T_run − l   moving up,      v ≥ −(p − p_min)/T_run − l   moving down,
// never past 0 (the limit does not reverse a joint), with p the position the command starts
// from. Away from a bound nothing is limited. Far from a bound the limit lies above the joints'
// C and changes nothing; it binds only in the last part of an approach, where (4.15)'s braking
// curve √(2μC·distance) is faster than distance/T_run (with the thesis' joints, μ 0.4 and
// C = w/2 ≈ 0.7 rad/s, and the shipped dog = 1, T_run ≈ 0.3 s: the last 0.05 rad; with dog = 4
// the last 0.6 rad, which makes every approach to a bound a slow creep). The load is taken to
// last through the run-on: a motor stalled by an obstacle that gives way just as the computer
// dies runs on faster than planned. With dog = 0 (no switch) nothing bounds the run-on and the
// command is returned unchanged. Throws std::invalid_argument for a negative T_run or a load
// that is not finite.
double run_on_limited_radps(double command_radps, double position_rad, double min_rad,
                            double max_rad, double run_on_s, double load_radps = 0.0);

// The time from a joint command to the joint's motion, seen from the position the driver has:
// µi samples p̄ when the request arrives and the driver gets it with the next cycle's frames
// (one period h old), and the motor follows a new duty with its lag τ. The response table of
// (4.4) measures the same chain up to the centre of µi's vel window: its mean delay
// h·Σ j·δ^j (the thesis' indexing) is τ + T(con)/2. So the dead time is
//   h + h·Σ j·δ^j − T(con)/2      (34 ms with the thesis' δ at 64 Hz: τ ≈ 18.5 ms).
// The joint laws plan from the position predicted that far ahead, p + v·dead time: a joint
// braking from 0.4 rad/s toward a bound otherwise passes it by 0.4 × 0.034 = 0.014 rad.
double joint_dead_time_s(const Params& params);

}  // namespace marsokhod::driver
