// The MuJoCo model (MJCF XML) of the rover on its terrain, generated from the geometry in Params
// (Figure 3.3) so that a changed config changes the simulated chassis.
//
// Bodies (x forward, y left, z up; the center unit's origin is the center of the center axle):
//   center_unit (free) ── wheel_CL, wheel_CR                      hinge about y
//     ├─ front_strut: length b from the center axle to the joint, pivoting about the center axle
//     │    │          (hinge strut_front)
//     │    └─ front_lever: length a from joint 6 to the exterior axle (joint_AF, p6 = −γf)
//     │         └─ front_axle: roll hinge θf about x (tilt_front, ±0.524 rad, passive)
//     │              └─ wheel_FL, wheel_FR                        hinge about y
//     └─ rear_strut (strut_rear) / rear_lever (joint_AR, p7 = +γr) / rear_axle (tilt_rear) /
//          wheel_BL, wheel_BR
// The two struts pivot freely about the center axle; an equality constraint keeps the center
// unit at their mean angle ("the central unit is tilted by ½(αf − αr)", Figure 3.3), so all six
// wheels stay on uneven ground while the joints hold their angles.
#pragma once

#include <cstddef>
#include <string>

#include "core/params.hpp"
#include "sim/physics/terrain.hpp"

namespace marsokhod::sim {

// Each motor (wheels and joint shafts alike) is a velocity servo τ = kv·(ctrl − ω) clipped to
// ±forcerange: the speed–torque line τ = (ω0 − ω)/droop with kv = 1/droop, ctrl = ω0,
// forcerange = stall, set by RoverPhysics, which also makes kv (≈ 33 N·m·s/rad) implicit through
// the Euler integrator's dof damping (rover_physics.cpp, apply_motor_lines). A joint's shaft
// reaches its joint only through the gap and the lock (joint_drive.hpp): equality constraints
// lock_<m> and couple_<m> and the hinges' limits, which RoverPhysics switches every step.
//
// Mass budget of the lab rover without the science payload of chapter 2 (which weighed 100 kg
// and more): motors, gears and batteries sit in the wheels.
inline constexpr double kCenterUnitMassKg = 30.0;
inline constexpr double kStrutMassKg = 3.0;   // each
inline constexpr double kLeverMassKg = 2.0;   // each
inline constexpr double kAxleMassKg = 3.0;    // each exterior axle beam
inline constexpr double kWheelMassKg = 6.0;   // each
inline constexpr double kWheelWidthM = 0.15;  // the 15 cm protective covers of chapter 3.1
// Each exterior axle's beam: a capsule of this radius between its wheels, ending this far inside
// each wheel's inner face.
inline constexpr double kAxleRadiusM = 0.04;
inline constexpr double kAxleEndGapM = 0.005;
// The Maxon RE 36 rotor (67.7 g·cm²) seen through a gear of ≈ 250:1 (about 7000 rpm to the
// 27 rpm of w = 2.827 rad/s): 6.77e-6 kg·m² · 250² ≈ 0.42 kg·m² at each motor's output shaft
// (chapter 4.2: all eight motors and gears are alike). It dwarfs a wheel's own 0.05 kg·m² and
// sets how fast a wheel spins up.
inline constexpr double kMotorReflectedInertiaKgM2 = 0.42;
// The joint motors' shafts are their own bodies (no collision, a token mass); the inertia that
// matters is the reflected rotor's, above.
inline constexpr double kShaftMassKg = 0.05;
// Stiffness of the constraints that make the gap's ends, the lock and the ratchet (MuJoCo's
// solref time constant): a few timesteps, so they hold a 40 N·m joint load within a milliradian.
inline constexpr double kConstraintTimeConstantS = 0.004;
// Light damping of the passive hinges (axle roll, strut pivots): the bearings' friction.
inline constexpr double kPassiveDampingNmsPerRad = 2.0;
// The strut pivots' travel about the center axle (not in the thesis; wide enough for a 0.3 m
// step under one exterior axle).
inline constexpr double kStrutPivotRangeRad = 0.6;

// Names in the generated model, shared with RoverPhysics (<m> is kMotorNames[motor]):
//   wheel_<m>    a wheel's body, hinge and geom          motor_<m>   motor m's actuator
//   joint_<m>    the hinge of joint 6 or 7 (p6, p7)      shaft_<m>   its motor's shaft (p̄6, p̄7)
//   lock_<m>     the lock holding joint <m>              couple_<m>  shaft bearing on the joint
//   block_<m>    the constraint that blocks a wheel
std::string wheel_name(std::size_t wheel);
std::string motor_actuator_name(std::size_t motor);
std::string joint_hinge_name(std::size_t motor);
std::string shaft_hinge_name(std::size_t motor);
std::string joint_lock_name(std::size_t motor);
std::string joint_coupling_name(std::size_t motor);
std::string wheel_block_name(std::size_t wheel);
inline constexpr const char* kCenterUnitName = "center_unit";
inline constexpr const char* kTestStandName = "test_stand";
inline constexpr const char* kFrontTiltName = "tilt_front";
inline constexpr const char* kRearTiltName = "tilt_rear";
inline constexpr const char* kImuSiteName = "imu";
inline constexpr const char* kAccelerometerName = "imu_accel";
inline constexpr const char* kRoverGeomClass = "rover";
inline constexpr int kRoverGeomGroup = 1;  // the ground is group 0 (ray casts select it)

// The complete model: options (timestep, the Euler integrator), the terrain, the rover with its
// actuators, sensors and equality constraints. The heightfield's elevations are not in the XML:
// load_rover_model() copies them into the compiled model.
std::string rover_mjcf(const Params& params, const TerrainSpec& terrain, double timestep_s);

}  // namespace marsokhod::sim
