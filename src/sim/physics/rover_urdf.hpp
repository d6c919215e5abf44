// The rover as a URDF (`marsokhod urdf`), for ROS tools, Foxglove's and PlotJuggler's 3-D views:
// the same chassis as the MuJoCo model (rover_mjcf.hpp), generated from the same Params.
//
// Links and joints (x forward, y left, z up; base_link is the center unit, its origin the center
// of the center axle):
//   base_link ── wheel_CL, wheel_CR                          continuous about y
//     ├─ strut_front (revolute, passive) front_strut
//     │    └─ joint_AF (revolute, p6 itself, limits (5.3): joints.front_min/max_rad) front_lever
//     │         └─ tilt_front (revolute about x, passive, ±0.524 rad) front_axle
//     │              └─ wheel_FL, wheel_FR                   continuous about y
//     └─ strut_rear (mimics strut_front × −1: the center unit at the struts' mean angle)
//          rear_strut / joint_AR (p7, joints.rear_min/max_rad) rear_lever / tilt_rear rear_axle /
//          wheel_BL, wheel_BR
// A joint's value is the model's hinge value, so joint_AF = p6 = −γf and joint_AR = p7 = +γr (the
// layout of rover_mjcf.hpp is the pose p6 = −acos(a/b), p7 = +acos(a/b)). Masses, centres of mass
// and inertia tensors are read from the compiled MuJoCo model (a body's inertia in its own frame);
// the motors' reflected rotor inertia (MuJoCo's armature) has no place in URDF and is left out, as
// are the joint motors' shafts (0.05 kg each) and the backlash between shaft and joint. A motor's
// effort limit is its stall torque in the driver's model (4.7): w / B⁺.
#pragma once

#include <string>

#include "core/params.hpp"

namespace marsokhod::sim {

// Throws std::invalid_argument for a geometry the model cannot be built from.
std::string rover_urdf(const Params& params);

}  // namespace marsokhod::sim
