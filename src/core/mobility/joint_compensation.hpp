// (5.1), (5.2): the wheel velocities n6·w6, n7·w7 that accompany a bending joint so that no wheel
// slips on flat ground, and the wheel-walking part m6 v6 + n6 w6 + m7 v7 + n7 w7 of (5.4).
//
//          [ (1−ρf)u    (1−ρf)u + ½·a(a − b cos γf)/cf²    −ρf·u − b(b − a cos γf)/cf² ]
//   n6  =  [                      0        0                                            ]   (5.1)
//          [ same as the first row                                                      ]
//   u = ab·sin γf / (r·cf)
//
//          [ −ρr·u − b(b − a cos γr)/cr²    (1−ρr)u + ½·a(a − b cos γr)/cr²    (1−ρr)u ]
//   n7  =  [                      0        0                                         ]   (5.2)
//          [ same as the first row                                                   ]
//   u = ab·sin γr / (r·cr)
//
// Columns are [rear, center, front] (BL/BR, CL/CR, FL/FR); entries are wheel rad per joint rad.
// Only u is divided by r: u = (∂c/∂γ)/r turns the change of the axle distance [m/rad] into a
// wheel angle, while b(b − a cos γ)/c² = ∂φ/∂γ and a(a − b cos γ)/c² = −∂α/∂γ (Lemma 5.3) are
// rates of angles: the lever turns under the wheel, which the motor (mounted on the lever) must
// cancel one to one. This placement reproduces Example 5.4's exterior columns to 4 digits
// (r = 0.125, γf = 2.1, ρf = 0.4: 0.4942 and −1.1261; r = 0.115, γr = 1.85, ρr = 0: −0.8329 and
// 1.0562); dividing an angle term by r as well, or u not by r, misses them by about 1/r = 8.
//
// The center column: center − far exterior column = ½·a(a − b cos γ)/c², which is the rate of
// the center unit's pitch ½(αf − αr) (Figure 3.3) per unit joint velocity: ½·∂αf/∂p6 for n6
// (p6 = −γf) and −½·∂αr/∂p7 for n7. The center wheels sit on the center unit and must cancel its
// pitch. The formula gives 0.5959 and 1.1398 for Example 5.4; the example prints 0.5331 and
// 1.0801, whose excess over the far column (0.0389, 0.0239) is no common multiple of the
// formula's (0.1017, 0.0836), so no placement of r explains them; docs/design.md keeps the formula.
//
// ρ ∈ [0, 1] in the thesis: ρ = 0 keeps the joint's own exterior axle still, ρ = 1 the other two
// axles. Any finite ρ is accepted (the ε-projection of chapter 5.3 may leave [0, 1]).
// Example at the contracted joint γ = acos(a/b), ρ = 1: the exterior wheel turns at −(1 + a/r)
// times the joint, −2.261 at r = 0.115 (the "factor of up to 2.261" of chapter 5.3).
#pragma once

#include "core/params.hpp"

namespace marsokhod::mobility {

// u of (5.1)/(5.2) for a bending γ [rad]: ab·sin γ/(r·c), wheel rad per joint rad.
double clearance_wheel_rate(double bending_rad, const GeometryParams& geometry);

// n6 (5.1) at the front joint position p6 [rad] (γf = −p6) with ρf.
MotorVector front_joint_compensation(double front_joint_position_rad, double front_axle_factor,
                                     const GeometryParams& geometry);

// n7 (5.2) at the rear joint position p7 [rad] (γr = +p7) with ρr.
MotorVector rear_joint_compensation(double rear_joint_position_rad, double rear_axle_factor,
                                    const GeometryParams& geometry);

// The wheel-walking terms of (5.4) for one cycle.
struct WalkingInput {
  double front_joint_position_rad = 0.0;    // p6
  double rear_joint_position_rad = 0.0;     // p7
  double front_joint_command_radps = 0.0;   // v6, the coefficient of m6
  double rear_joint_command_radps = 0.0;    // v7, the coefficient of m7
  double front_joint_velocity_radps = 0.0;  // w6, the measured joint velocity (coefficient of n6)
  double rear_joint_velocity_radps = 0.0;   // w7
  double front_axle_factor = 0.0;           // ρf
  double rear_axle_factor = 0.0;            // ρr
};

// m6 v6 + n6 w6 + m7 v7 + n7 w7 [rad/s].
MotorVector walking_motion(const WalkingInput& input, const GeometryParams& geometry);

}  // namespace marsokhod::mobility
