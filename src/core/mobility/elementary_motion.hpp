// The elementary motions m1, m2, m3, m4, m6, m7 of chapter 5 as motor vectors in the layout (3.1):
//
//        [ BL,4  CL,2  FL,0 ]
//   m =  [    AB,7  AF,6    ]      ŵ = m·v assigns the velocity m_i·v [rad/s] to motor i
//        [ BR,5  CR,3  FR,1 ]
//
//   m1 drive straight     [ 1 1 1 ; 0 0 ; 1 1 1 ]                      (SPEC: lost in a figure)
//   m2 spin (5.1)         [ −F(cr) −1 −F(cf) ; 0 0 ; F(cr) 1 F(cf) ]   F(c) = slope·c + offset
//   m3 sideways drift     [ 1 0 −1 ; 0 0 ; −1 0 1 ]
//   m4 trench             1 on FR only                                 (SPEC)
//   m6 bend front joint   1 on AF (motor 6) only                       (SPEC)
//   m7 bend rear joint    1 on AB (motor 7) only                       (SPEC)
//
// A positive wheel velocity drives forward. So v2 > 0 turns the left side backward and the right
// side forward: the rover turns counter-clockwise seen from above (to the left), around the
// center of the center axle; v2 < 0 turns clockwise. F(c) is the exterior-to-center speed ratio of
// Procedure 5.1 (5.3·c + 0.04: F(0.387) = 2.09, F(0.539) = 2.90).
//
// Chapter 5's example: 0.27 m/s forward on r = 0.12 m wheels is m1·v1 with v1 = 0.27/0.12 = 2.25.
#pragma once

#include "core/params.hpp"

namespace marsokhod::mobility {

MotorVector drive_straight_motion();  // m1
MotorVector sideways_drift_motion();  // m3
MotorVector trench_motion();          // m4
MotorVector front_joint_motion();     // m6
MotorVector rear_joint_motion();      // m7

// F(c) = slope·c + offset (chapter 5.1). Throws std::invalid_argument on a non-finite argument.
double spin_ratio(double clearance_m, const SpinParams& spin);

// m2 for the clearances cf, cr [m] of the front and rear levers.
MotorVector spin_motion(double front_clearance_m, double rear_clearance_m, const SpinParams& spin);

// The coefficients v1..v4 of the driving part of (5.4) [rad/s].
struct DrivingSpeeds {
  double drive_radps = 0.0;   // v1
  double spin_radps = 0.0;    // v2 (> 0: counter-clockwise seen from above)
  double drift_radps = 0.0;   // v3
  double trench_radps = 0.0;  // v4 (> 0: FR turns forward)
};

// Σ_{j=1..4} m_j v_j: the part of (5.4) that (5.5) may scale by κ.
MotorVector driving_motion(const DrivingSpeeds& speeds, double front_clearance_m,
                           double rear_clearance_m, const SpinParams& spin);

// into += motion·coefficient (one term m_j v_j of (5.4)); throws on a non-finite coefficient.
void add_scaled(MotorVector& into, const MotorVector& motion, double coefficient);

}  // namespace marsokhod::mobility
