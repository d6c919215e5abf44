// The simulator benchmarks' bare MuJoCo rover: the generated model stepped by mj_step alone, to
// measure what the stack around MuJoCo costs (sim_physics_bench, sim_rover_bench).
#pragma once

#include <array>

#include "sim/physics/mujoco_model.hpp"
#include "sim/physics/rover_mjcf.hpp"
#include "sim/physics/rover_physics.hpp"

namespace marsokhod::sim {

// The wheels' drive of the benchmarks: 2 rad/s no-load, the motors' droop and stall torque.
inline MotorDrive cruise() {
  MotorDrive drive;
  for (std::size_t motor = 0; motor < kMotorCount; ++motor) {
    drive.no_load_speed_radps[motor] = motor < kWheelCount ? 2.0 : 0.0;
    drive.droop_radps_per_nm[motor] = 0.030;
    drive.stall_torque_nm[motor] = 94.0;
  }
  return drive;
}

inline constexpr int kBareSettleSteps = 300;

// The same model stepped by MuJoCo alone: the wheels' servos and the joints' locks set once, as
// RoverPhysics sets them, the rover placed on the ground and settled.
struct BareRover {
  ModelPtr model;
  DataPtr data;
  std::array<int, kWheelCount> wheel_dofs{};
};

// One step as RoverPhysics makes it: the wheels' lines implicit through their dofs' damping (the
// Euler integrator), the damping's own force cancelled by an applied one (rover_physics.cpp,
// apply_motor_lines), then mj_step.
inline void step_bare(BareRover& rover) {
  const mjModel* model = rover.model.get();
  mjData* data = rover.data.get();
  for (int dof : rover.wheel_dofs) {
    data->qfrc_applied[dof] = model->dof_damping[dof] * data->qvel[dof];
  }
  mj_step(model, data);
}

inline BareRover bare_rover(const TerrainSpec& terrain, double timestep_s) {
  const Params params;
  BareRover rover{load_rover_model(params, terrain, timestep_s), nullptr};
  mjModel* model = rover.model.get();
  rover.data.reset(mj_makeData(model));
  const MotorDrive drive = cruise();
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    const int actuator = require_id(*model, mjOBJ_ACTUATOR, motor_actuator_name(wheel));
    model->actuator_gainprm[actuator * mjNGAIN] = 1.0 / drive.droop_radps_per_nm[wheel];
    model->actuator_biasprm[actuator * mjNBIAS + 2] = -1.0 / drive.droop_radps_per_nm[wheel];
    model->actuator_forcerange[actuator * 2] = -drive.stall_torque_nm[wheel];
    model->actuator_forcerange[actuator * 2 + 1] = drive.stall_torque_nm[wheel];
    rover.data->ctrl[actuator] = drive.no_load_speed_radps[wheel];
    const int dof = model->jnt_dofadr[require_id(*model, mjOBJ_JOINT, wheel_name(wheel))];
    model->dof_damping[dof] = 1.0 / drive.droop_radps_per_nm[wheel];
    rover.wheel_dofs[wheel] = dof;
  }
  for (std::size_t motor : {kFrontJoint, kRearJoint}) {
    model->eq_active[require_id(*model, mjOBJ_EQUALITY, joint_lock_name(motor))] = 1;
  }
  rover.data->qpos[2] = params.geometry.wheel_radius_m + 0.005;
  for (int i = 0; i < kBareSettleSteps; ++i) step_bare(rover);
  return rover;
}

}  // namespace marsokhod::sim
