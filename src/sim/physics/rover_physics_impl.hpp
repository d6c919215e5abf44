// RoverPhysics' state, shared by rover_physics.cpp (building, stepping, faults) and
// rover_truth.cpp (what tests and the 3-D view read). Not part of the public API.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "sim/physics/joint_drive.hpp"
#include "sim/physics/mujoco_model.hpp"
#include "sim/physics/rover_physics.hpp"
#include "sim/soil/soft_soil.hpp"

namespace marsokhod::sim {

// Addresses of the model's named parts, looked up once. Arrays of two are [0] front, [1] rear.
struct RoverModelIds {
  int center_body = -1;
  int free_qpos = -1;  // x y z, quaternion w x y z
  int free_dof = -1;   // world linear velocity, then body-frame angular velocity
  std::array<int, kMotorCount> motor_actuator{};
  std::array<int, kMotorCount> shaft_qpos{}, shaft_dof{};  // wheels: the wheel's hinge
  std::array<int, kWheelCount> wheel_body{}, wheel_geom{}, wheel_block{};
  std::array<int, 2> joint_hinge{}, shaft_hinge{};  // joint ids, for their ranges
  std::array<int, 2> joint_qpos{}, joint_lock{}, joint_coupling{};
  std::array<int, 2> tilt_qpos{}, tilt_dof{};
  std::array<int, 2> strut_qpos{};  // the passive pivots strut_front, strut_rear
  int accelerometer = -1;  // sensordata address
  int stand_weld = -1;     // equality holding the center unit on the calibration stand
  int stand_mocap = -1;    // the stand's mocap index
};

struct RoverPhysics::Impl {
  Impl(const Params& params, const TerrainSpec& terrain, double timestep_s);

  void resolve_ids();
  void start_joints();
  void place_on_terrain(const TerrainSpec& terrain);
  void apply_drive();
  void update_joint_modes();
  void apply_joint_mode(std::size_t slot);
  void apply_joint_lock_brake(std::size_t slot, double no_load_speed_radps);
  void build_soft_soil(const TerrainSpec& terrain);
  void apply_soft_soil();

  Params params;
  ModelPtr model;
  DataPtr data;
  RoverModelIds ids;
  MotorDrive drive{};
  bool powered = false;  // false until the first set_drive: the motors deliver no torque
  std::array<JointDrive, 2> joints;
  // A jammed joint (set_joint_jammed): the joint's and the shaft's angles it is held at.
  std::array<std::optional<std::array<double, 2>>, 2> jammed_rad{};
  std::array<bool, 2> joint_overrun{};  // a pushing shaft ahead of ω0, braked by the lock
  std::array<std::array<double, 2>, 2> joint_stops_rad{}, shaft_stops_rad{};  // the model's ranges
  // Weights strapped to wheels (Procedure 4.13): peak gravity torque per wheel [N·m], 0 for none.
  std::array<double, kWheelCount> strapped_peak_torque_nm{};
  void apply_strapped_weights();
  // The torque applied to each shaft this step besides its motor (the strapped weights), and
  // each shaft's own damping in the model (apply_motor_lines adds its motor's kv to it).
  std::array<double, kMotorCount> shaft_applied_nm{};
  std::array<double, kMotorCount> shaft_own_damping{};
  void apply_motor_lines();
  // Procedure 3.4's hands on the exterior axles: the angle each is turned to (nullopt: none), and
  // where the hand is now.
  std::array<std::optional<double>, 2> axle_hand_target_rad{};
  std::array<double, 2> axle_hand_rad{}, axle_hand_speed_radps{};
  void move_axle_hands();
  void pin_axles_to_hands();
  // Soft soil under the wheels (rover_soft_soil.cpp), when the ground's material has one.
  std::optional<soil::SoftSoil> soft_soil;
  std::array<soil::WheelWrench, kWheelCount> soil_wrenches{};  // the last step's
  // The height field the chassis meets on soft soil (rover_soft_soil.cpp): its id and its geom's,
  // the ground's cos α, its plane and normal, the geoms that can meet it, the steps since it last
  // took the grid's changes and how many make its period.
  int soil_field = -1, soil_field_geom = -1;
  double soil_field_cos = 1.0;
  double soil_field_slope = 0.0;  // tan α of the ground's plane
  double soil_field_above = 0.0;  // the field's top over the plane (soil_field_above_m)
  std::vector<double> soil_field_plane;  // the plane's height at each column's cells' centres
  std::array<double, 3> soil_field_normal{0.0, 0.0, 1.0};
  std::vector<int> soil_field_geoms;
  void copy_soil_to_field();
  void follow_with_soil_window();
  void place_soil_field_plane();
  bool chassis_near_soil() const;
  void update_soil_field();
};

}  // namespace marsokhod::sim
