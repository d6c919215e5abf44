#include "sim/physics/rover_physics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "sim/physics/chassis_geometry.hpp"
#include "sim/physics/rover_mjcf.hpp"
#include "sim/physics/rover_physics_impl.hpp"

namespace marsokhod::sim {
namespace {

// The rover starts this far above the ground and settles onto it in the first steps.
constexpr double kStartClearanceM = 0.005;
constexpr double kRayStartHeightM = 1000.0;

constexpr std::array<std::size_t, 2> kJointMotors{kFrontJoint, kRearJoint};

// The joint lock's brake on a shaft running ahead of its motor (apply_joint_lock_brake): stiff
// enough that a 40 N·m aiding load overruns ω0 by 4 mrad/s; the lock bears up to 1000 N·m.
constexpr double kLockBrakeGainNmsPerRad = 1e4;
constexpr double kLockBrakeTorqueNm = 1000.0;

JointDrive joint_drive_for(const Params& params, std::size_t motor) {
  return JointDrive(params.motors.initial_position_rad[motor], params.motors.backlash_rad[motor]);
}

void check_initial_joint(const Params& params, std::size_t motor) {
  const BendRange range = mechanical_bend_range(params.geometry);
  const double bend_rad = motor == kFrontJoint ? -params.motors.initial_position_rad[motor]
                                               : params.motors.initial_position_rad[motor];
  if (!(bend_rad >= range.min_rad && bend_rad <= range.max_rad) ||
      !(params.motors.backlash_rad[motor] >= 0.0)) {
    throw std::invalid_argument(
        std::string("physics: the initial position of joint ") + kMotorNames[motor] +
        " lies outside its mechanical range (γ in [" + std::to_string(range.min_rad) + ", " +
        std::to_string(range.max_rad) + "] rad) or its backlash is negative");
  }
}

// The height of the terrain's geoms (group 0) under (x, y), by a ray cast down from
// kRayStartHeightM; NaN where it meets none.
double terrain_ray_height_m(const mjModel& model, mjData& data, double x_m, double y_m) {
  std::array<mjtByte, mjNGROUP> terrain_only{};
  terrain_only[0] = 1;
  const mjtNum start[3] = {x_m, y_m, kRayStartHeightM};
  const mjtNum down[3] = {0.0, 0.0, -1.0};
  int geom = -1;
  const mjtNum distance = mj_ray(&model, &data, start, down, terrain_only.data(), 1, -1, &geom);
  return distance >= 0.0 ? kRayStartHeightM - distance : std::numeric_limits<double>::quiet_NaN();
}

// The highest terrain under one wheel, by casting rays down onto the terrain only at 3 × 3 points
// over its footprint.
double ground_height_under_wheel_m(const mjModel& model, mjData& data, int body,
                                   double radius_m) {
  double highest_m = -kRayStartHeightM;
  for (double dx : {-0.7 * radius_m, 0.0, 0.7 * radius_m}) {
    for (double dy : {-kWheelWidthM / 2, 0.0, kWheelWidthM / 2}) {
      const double height_m = terrain_ray_height_m(model, data, data.xpos[3 * body] + dx,
                                                   data.xpos[3 * body + 1] + dy);
      if (!std::isnan(height_m)) highest_m = std::max(highest_m, height_m);
    }
  }
  return highest_m;
}

// The highest ground under all the wheels' footprints.
double ground_height_under_wheels_m(const mjModel& model, mjData& data, const RoverModelIds& ids,
                                    double radius_m) {
  double highest_m = -kRayStartHeightM;
  for (int body : ids.wheel_body) {
    highest_m = std::max(highest_m, ground_height_under_wheel_m(model, data, body, radius_m));
  }
  return highest_m;
}

}  // namespace

RoverPhysics::Impl::Impl(const Params& params_in, const TerrainSpec& terrain, double timestep_s)
    : params(params_in),
      model(load_rover_model(params_in, terrain, timestep_s)),
      data(mj_makeData(model.get())),
      joints{joint_drive_for(params_in, kFrontJoint), joint_drive_for(params_in, kRearJoint)} {
  if (!data) throw std::runtime_error("physics: MuJoCo could not allocate its data");
  check_initial_joint(params, kFrontJoint);
  check_initial_joint(params, kRearJoint);
  resolve_ids();
  for (std::size_t motor = 0; motor < kMotorCount; ++motor) {
    shaft_own_damping[motor] = model->dof_damping[ids.shaft_dof[motor]];
  }
  start_joints();
  build_soft_soil(terrain);  // first: the rover is set down on the soil's field (a heightfield's)
  place_on_terrain(terrain);
  mj_forward(model.get(), data.get());
  if (soft_soil) update_soil_field();  // with the chassis where it now stands
}

void RoverPhysics::Impl::resolve_ids() {
  const mjModel& m = *model;
  ids.center_body = require_id(m, mjOBJ_BODY, kCenterUnitName);
  const int free_joint = require_id(m, mjOBJ_JOINT, kCenterUnitName);
  ids.free_qpos = m.jnt_qposadr[free_joint];
  ids.free_dof = m.jnt_dofadr[free_joint];
  for (std::size_t motor = 0; motor < kMotorCount; ++motor) {
    const bool wheel = motor < kWheelCount;
    const int shaft =
        require_id(m, mjOBJ_JOINT, wheel ? wheel_name(motor) : shaft_hinge_name(motor));
    ids.shaft_qpos[motor] = m.jnt_qposadr[shaft];
    ids.shaft_dof[motor] = m.jnt_dofadr[shaft];
    ids.motor_actuator[motor] = require_id(m, mjOBJ_ACTUATOR, motor_actuator_name(motor));
    if (wheel) {
      ids.wheel_body[motor] = require_id(m, mjOBJ_BODY, wheel_name(motor));
      ids.wheel_geom[motor] = require_id(m, mjOBJ_GEOM, wheel_name(motor));
      ids.wheel_block[motor] = require_id(m, mjOBJ_EQUALITY, wheel_block_name(motor));
    } else {
      const std::size_t slot = motor - kFrontJoint;
      ids.shaft_hinge[slot] = shaft;
      ids.joint_hinge[slot] = require_id(m, mjOBJ_JOINT, joint_hinge_name(motor));
      ids.joint_qpos[slot] = m.jnt_qposadr[ids.joint_hinge[slot]];
      ids.joint_lock[slot] = require_id(m, mjOBJ_EQUALITY, joint_lock_name(motor));
      ids.joint_coupling[slot] = require_id(m, mjOBJ_EQUALITY, joint_coupling_name(motor));
    }
  }
  ids.tilt_qpos[0] = m.jnt_qposadr[require_id(m, mjOBJ_JOINT, kFrontTiltName)];
  ids.tilt_qpos[1] = m.jnt_qposadr[require_id(m, mjOBJ_JOINT, kRearTiltName)];
  ids.tilt_dof[0] = m.jnt_dofadr[require_id(m, mjOBJ_JOINT, kFrontTiltName)];
  ids.tilt_dof[1] = m.jnt_dofadr[require_id(m, mjOBJ_JOINT, kRearTiltName)];
  ids.strut_qpos[0] = m.jnt_qposadr[require_id(m, mjOBJ_JOINT, "strut_front")];
  ids.strut_qpos[1] = m.jnt_qposadr[require_id(m, mjOBJ_JOINT, "strut_rear")];
  ids.accelerometer = m.sensor_adr[require_id(m, mjOBJ_SENSOR, kAccelerometerName)];
  ids.stand_weld = require_id(m, mjOBJ_EQUALITY, kTestStandName);
  ids.stand_mocap = m.body_mocapid[require_id(m, mjOBJ_BODY, kTestStandName)];
}

// Each joint starts locked at its initial angle (Remark 3.1: vertical) with the shaft at the
// gap's upper end, so that Procedure 4.3's push toward the negative end crosses the whole gap
// before it could move the joint (the thesis' premise: the joint stays vertical).
void RoverPhysics::Impl::start_joints() {
  for (std::size_t slot = 0; slot < 2; ++slot) {
    for (int side = 0; side < 2; ++side) {
      joint_stops_rad[slot][side] = model->jnt_range[2 * ids.joint_hinge[slot] + side];
      shaft_stops_rad[slot][side] = model->jnt_range[2 * ids.shaft_hinge[slot] + side];
    }
    data->qpos[ids.joint_qpos[slot]] = joints[slot].held_angle_rad();
    data->qpos[ids.shaft_qpos[kJointMotors[slot]]] =
        joints[slot].held_angle_rad() + joints[slot].backlash_rad();
    apply_joint_mode(slot);
  }
}

// On a slope the rover stands square to the plane; elsewhere level, just above the highest
// ground under its wheels.
void RoverPhysics::Impl::place_on_terrain(const TerrainSpec& terrain) {
  mjtNum* pose = data->qpos + ids.free_qpos;
  const double height_m = params.geometry.wheel_radius_m + kStartClearanceM;
  if (terrain.kind == TerrainKind::kSlope) {
    const double slope_rad = terrain.slope_rad;
    pose[0] = -std::sin(slope_rad) * height_m;
    pose[1] = 0.0;
    pose[2] = std::cos(slope_rad) * height_m;
    pose[3] = std::cos(-slope_rad / 2);  // nose up: a negative rotation about y
    pose[4] = 0.0;
    pose[5] = std::sin(-slope_rad / 2);
    pose[6] = 0.0;
    return;
  }
  pose[0] = pose[1] = pose[2] = 0.0;
  pose[3] = 1.0;
  pose[4] = pose[5] = pose[6] = 0.0;
  mj_kinematics(model.get(), data.get());
  pose[2] =
      ground_height_under_wheels_m(*model, *data, ids, params.geometry.wheel_radius_m) + height_m;
}

void RoverPhysics::Impl::apply_drive() {
  mjModel& m = *model;
  for (std::size_t motor = 0; motor < kMotorCount; ++motor) {
    const int actuator = ids.motor_actuator[motor];
    const double gain = powered ? 1.0 / drive.droop_radps_per_nm[motor] : 0.0;
    m.actuator_gainprm[actuator * mjNGAIN] = gain;
    m.actuator_biasprm[actuator * mjNBIAS + 2] = -gain;
    // A torque along the shaft's motion (or holding it still) is the motor's, at most τ_stall. A
    // wheel's torque against its motion is a generating or plugging motor's: its back-EMF adds
    // to the current, so the bound grows from τ_stall by |ω|/B (the line's own slope), up to the
    // brake torque. Joints keep τ_stall both ways: their lock bears a load that drives them
    // (apply_joint_lock_brake).
    const double stall = drive.stall_torque_nm[motor];
    const double speed_radps = data->qvel[ids.shaft_dof[motor]];
    const double against =
        motor < kWheelCount
            ? std::clamp(stall + std::abs(speed_radps) / drive.droop_radps_per_nm[motor], stall,
                         std::max(stall, drive.brake_torque_nm[motor]))
            : stall;
    m.actuator_forcerange[actuator * 2] = speed_radps > 0.0 ? -against : -stall;
    m.actuator_forcerange[actuator * 2 + 1] = speed_radps < 0.0 ? against : stall;
    data->ctrl[actuator] = drive.no_load_speed_radps[motor];
  }
}

void RoverPhysics::Impl::update_joint_modes() {
  for (std::size_t slot = 0; slot < 2; ++slot) {
    const std::size_t motor = kJointMotors[slot];
    const double command_radps = powered ? drive.no_load_speed_radps[motor] : 0.0;
    joints[slot].update(data->qpos[ids.shaft_qpos[motor]], data->qpos[ids.joint_qpos[slot]],
                        command_radps);
    apply_joint_mode(slot);
    apply_joint_lock_brake(slot, command_radps);
  }
}

// The mode as MuJoCo constraints. Locked: the lock holds the joint, the gap's ends bound the shaft.
// Pushing: the coupling makes p = p̄ + offset, and the joint's stop behind it follows the furthest
// angle reached (the lock as a ratchet), so no load drives joint or shaft backwards.
void RoverPhysics::Impl::apply_joint_mode(std::size_t slot) {
  mjModel& m = *model;
  const JointDrive& joint = joints[slot];
  const int joint_qpos = ids.joint_qpos[slot];
  const int shaft_qpos = ids.shaft_qpos[kJointMotors[slot]];
  const bool locked = joint.mode() == JointMode::kLocked;
  m.eq_active[ids.joint_lock[slot]] = locked ? 1 : 0;
  m.eq_active[ids.joint_coupling[slot]] = locked ? 0 : 1;
  // MuJoCo's joint equality: q1 − q1₀ = c0 + c1·(q2 − q2₀).
  m.eq_data[ids.joint_lock[slot] * mjNEQDATA] = joint.held_angle_rad() - m.qpos0[joint_qpos];
  m.eq_data[ids.joint_coupling[slot] * mjNEQDATA] =
      joint.coupling_offset_rad() - m.qpos0[joint_qpos] + m.qpos0[shaft_qpos];
  mjtNum* joint_range = m.jnt_range + 2 * ids.joint_hinge[slot];
  mjtNum* shaft_range = m.jnt_range + 2 * ids.shaft_hinge[slot];
  joint_range[0] = joint_stops_rad[slot][0];
  joint_range[1] = joint_stops_rad[slot][1];
  shaft_range[0] = shaft_stops_rad[slot][0];
  shaft_range[1] = shaft_stops_rad[slot][1];
  if (const auto& jam = jammed_rad[slot]) {  // the lock at the jam, the shaft pinned
    m.eq_active[ids.joint_lock[slot]] = 1;
    m.eq_active[ids.joint_coupling[slot]] = 0;
    m.eq_data[ids.joint_lock[slot] * mjNEQDATA] = (*jam)[0] - m.qpos0[joint_qpos];
    shaft_range[0] = shaft_range[1] = (*jam)[1];
  } else if (locked) {
    shaft_range[0] = joint.held_angle_rad();
    shaft_range[1] = joint.held_angle_rad() + joint.backlash_rad();
  } else if (joint.mode() == JointMode::kPushingUp) {
    joint_range[0] = std::max(joint_range[0], joint.held_angle_rad());
  } else {
    joint_range[1] = std::min(joint_range[1], joint.held_angle_rad());
  }
}

// The lock while pushing: a load that aids the motor (gravity on a lever that swings down) cannot
// turn the joint faster than the motor turns it — the lock carries the excess, not the motor. So a
// pushing shaft that runs ahead of its no-load speed ω0 meets a stiff brake at ω0 (the lock);
// below ω0 the motor's speed–torque line applies unchanged. The brake is the motor's actuator
// with a stiffer line and a braking limit of the lock's, switched each step by the shaft's speed;
// shaft_torque_nm() still reports the motor's own torque on its line.
void RoverPhysics::Impl::apply_joint_lock_brake(std::size_t slot, double no_load_speed_radps) {
  const std::size_t motor = kJointMotors[slot];
  const int actuator = ids.motor_actuator[motor];
  const double speed_radps = data->qvel[ids.shaft_dof[motor]];
  const bool pushing = joints[slot].mode() != JointMode::kLocked;
  const bool overrun = powered && pushing &&
                       (no_load_speed_radps > 0.0 ? speed_radps > no_load_speed_radps
                                                  : speed_radps < no_load_speed_radps);
  joint_overrun[slot] = overrun;
  if (!powered) return;
  mjModel& m = *model;
  const double stall = drive.stall_torque_nm[motor];
  const double gain = overrun ? kLockBrakeGainNmsPerRad : 1.0 / drive.droop_radps_per_nm[motor];
  m.actuator_gainprm[actuator * mjNGAIN] = gain;
  m.actuator_biasprm[actuator * mjNBIAS + 2] = -gain;
  m.actuator_forcerange[actuator * 2] =
      overrun && no_load_speed_radps > 0.0 ? -kLockBrakeTorqueNm : -stall;
  m.actuator_forcerange[actuator * 2 + 1] =
      overrun && no_load_speed_radps < 0.0 ? kLockBrakeTorqueNm : stall;
}

RoverPhysics::RoverPhysics(const Params& params, const TerrainSpec& terrain, double timestep_s)
    : impl_(std::make_unique<Impl>(params, terrain, timestep_s)) {}

RoverPhysics::~RoverPhysics() = default;

void RoverPhysics::set_drive(const MotorDrive& drive) {
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    if (!std::isfinite(drive.no_load_speed_radps[i]) || !(drive.droop_radps_per_nm[i] > 0.0) ||
        !std::isfinite(drive.droop_radps_per_nm[i]) || !(drive.stall_torque_nm[i] >= 0.0) ||
        !std::isfinite(drive.stall_torque_nm[i]) || !(drive.brake_torque_nm[i] >= 0.0) ||
        !std::isfinite(drive.brake_torque_nm[i])) {
      throw std::invalid_argument(std::string("physics: the drive of motor ") + kMotorNames[i] +
                                  " needs a finite speed, droop > 0, and stall and brake torques"
                                  " >= 0");
    }
  }
  impl_->drive = drive;
  impl_->powered = true;
  impl_->apply_drive();
}

void RoverPhysics::Impl::apply_strapped_weights() {
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    // A weight at the rim's angle φ (the wheel's hinge angle, 0 with the weight at the top):
    // gravity pulls it down the rim, τ = peak·sin φ about the hinge.
    const double peak = strapped_peak_torque_nm[wheel];
    shaft_applied_nm[wheel] =
        peak == 0.0 ? 0.0 : peak * std::sin(data->qpos[ids.shaft_qpos[wheel]]);
  }
}

// Each motor's line τ = kv·(ω0 − ω), clipped at ±forcerange, is MuJoCo's actuator, and its
// velocity gain kv is integrated implicitly, as MuJoCo's "implicit" integrator did. It must be for
// the joint lock's brake (kv = 10⁴ on 0.42 kg m²: h·kv/I ≈ 24 at 1 ms, far past an explicit
// step's limit of 2); the lines' own 1/droop ≈ 33 N·m·s/rad (h·kv/I ≈ 0.07) would be stable
// either way, and implicit they keep the numbers the scenarios were written on. The Euler
// integrator solves (M + h·B)·a = f with B the dofs' damping, so each shaft's damping is set to
// its own plus its actuator's kv, and the damping force −kv·ω that MuJoCo then adds to f is
// cancelled by +kv·ω applied (the same ω, the step's start): f stays what it was, and the step
// is the one the implicit integrator made with the actuators' derivative −kv (MuJoCo 2.2 takes it
// even for a clipped actuator, as here) — without the Coriolis forces' derivative, which cost
// half of every step. Also before each mj_forward outside a step, so that its accelerations see
// the same forces.
void RoverPhysics::Impl::apply_motor_lines() {
  mjModel& m = *model;
  for (std::size_t motor = 0; motor < kMotorCount; ++motor) {
    const int dof = ids.shaft_dof[motor];
    const double kv = -m.actuator_biasprm[ids.motor_actuator[motor] * mjNBIAS + 2];
    m.dof_damping[dof] = shaft_own_damping[motor] + kv;
    data->qfrc_applied[dof] = shaft_applied_nm[motor] + kv * data->qvel[dof];
  }
}

void RoverPhysics::Impl::move_axle_hands() {
  const double step_rad = kAxleHandRateRadps * model->opt.timestep;
  for (std::size_t axle = 0; axle < 2; ++axle) {
    if (!axle_hand_target_rad[axle]) continue;
    const double target =
        std::clamp(*axle_hand_target_rad[axle], -kMaxAxleTiltRad, kMaxAxleTiltRad);
    const double move = std::clamp(target - axle_hand_rad[axle], -step_rad, step_rad);
    axle_hand_rad[axle] += move;
    axle_hand_speed_radps[axle] = move / model->opt.timestep;
  }
}

void RoverPhysics::Impl::pin_axles_to_hands() {
  // Kinematic: the hand is rigid, so the hinge is where the hand is, moving at its speed —
  // before the step (what the dynamics see) and after it (what is read).
  for (std::size_t axle = 0; axle < 2; ++axle) {
    if (!axle_hand_target_rad[axle]) continue;
    data->qpos[ids.tilt_qpos[axle]] = axle_hand_rad[axle];
    data->qvel[ids.tilt_dof[axle]] = axle_hand_speed_radps[axle];
  }
}

void RoverPhysics::step() {
  impl_->update_joint_modes();
  impl_->apply_strapped_weights();
  impl_->move_axle_hands();
  impl_->pin_axles_to_hands();
  impl_->apply_soft_soil();
  impl_->apply_motor_lines();
  mj_step(impl_->model.get(), impl_->data.get());
  impl_->pin_axles_to_hands();
}

void RoverPhysics::place_on_stand(double roll_rad, double pitch_rad) {
  if (!std::isfinite(roll_rad) || !std::isfinite(pitch_rad)) {
    throw std::invalid_argument("physics: the stand's roll and pitch must be finite");
  }
  mjModel& m = *impl_->model;
  mjData& d = *impl_->data;
  const RoverModelIds& ids = impl_->ids;
  // R = Ry(pitch)·Rx(roll): roll about x1 first, then pitch about the world's y.
  const double cr = std::cos(roll_rad / 2), sr = std::sin(roll_rad / 2);
  const double cp = std::cos(pitch_rad / 2), sp = std::sin(pitch_rad / 2);
  const std::array<double, 4> quat{cp * cr, cp * sr, sp * cr, -sp * sr};
  // 1 m above where the rover stood (the stand's own height when it is already on it).
  const bool already = m.eq_active[ids.stand_weld] != 0;
  const std::array<double, 3> position{
      d.qpos[ids.free_qpos], d.qpos[ids.free_qpos + 1],
      already ? d.mocap_pos[3 * ids.stand_mocap + 2] : d.qpos[ids.free_qpos + 2] + 1.0};
  for (int i = 0; i < 3; ++i) d.mocap_pos[3 * ids.stand_mocap + i] = position[i];
  for (int i = 0; i < 4; ++i) d.mocap_quat[4 * ids.stand_mocap + i] = quat[i];
  for (int i = 0; i < 3; ++i) d.qpos[ids.free_qpos + i] = position[i];
  for (int i = 0; i < 4; ++i) d.qpos[ids.free_qpos + 3 + i] = quat[i];
  for (int i = 0; i < 6; ++i) d.qvel[ids.free_dof + i] = 0.0;
  m.eq_active[ids.stand_weld] = 1;
  impl_->apply_motor_lines();
  mj_forward(&m, &d);
}

void RoverPhysics::place_on_ground() {
  mjModel& m = *impl_->model;
  mjData& d = *impl_->data;
  const RoverModelIds& ids = impl_->ids;
  if (m.eq_active[ids.stand_weld] == 0) return;
  m.eq_active[ids.stand_weld] = 0;
  // Level, just above the ground under the wheels where the stand stood.
  const double x = d.qpos[ids.free_qpos];
  const double y = d.qpos[ids.free_qpos + 1];
  d.qpos[ids.free_qpos + 2] = 0.0;
  d.qpos[ids.free_qpos + 3] = 1.0;
  for (int i = 4; i < 7; ++i) d.qpos[ids.free_qpos + i] = 0.0;
  for (int i = 0; i < 6; ++i) d.qvel[ids.free_dof + i] = 0.0;
  mj_kinematics(&m, &d);
  // The joints set on the stand may hang the exterior axles below the centre one: the rover goes
  // down until its first wheel is kStartClearanceM above the ground under it, none below.
  const double radius_m = impl_->params.geometry.wheel_radius_m;
  double height_m = -kRayStartHeightM;
  for (int body : ids.wheel_body) {
    height_m = std::max(height_m, ground_height_under_wheel_m(m, d, body, radius_m) + radius_m +
                                      kStartClearanceM - d.xpos[3 * body + 2]);
  }
  d.qpos[ids.free_qpos + 2] = height_m;
  d.qpos[ids.free_qpos] = x;
  d.qpos[ids.free_qpos + 1] = y;
  impl_->apply_motor_lines();
  mj_forward(&m, &d);
  // On soft soil: whether the chassis meets the soil's field is decided anew where it now stands.
  if (impl_->soft_soil) impl_->update_soil_field();
}

const soil::SoftSoil* RoverPhysics::soft_soil() const {
  return impl_->soft_soil ? &*impl_->soft_soil : nullptr;
}

soil::SoftSoil* RoverPhysics::soft_soil() {
  return impl_->soft_soil ? &*impl_->soft_soil : nullptr;
}

double RoverPhysics::terrain_height_m(double x_m, double y_m) const {
  return terrain_ray_height_m(*impl_->model, *impl_->data, x_m, y_m);
}

bool RoverPhysics::soil_field_met() const {
  return impl_->soft_soil && impl_->model->geom_conaffinity[impl_->soil_field_geom] != 0;
}

void RoverPhysics::level_soil() {
  if (!impl_->soft_soil) return;
  impl_->soft_soil->level();
  impl_->update_soil_field();
}

bool RoverPhysics::on_stand() const { return impl_->model->eq_active[impl_->ids.stand_weld] != 0; }

void RoverPhysics::strap_weight(std::size_t wheel, double peak_torque_nm) {
  if (wheel >= kWheelCount) throw std::out_of_range("physics: no wheel " + std::to_string(wheel));
  if (!std::isfinite(peak_torque_nm) || peak_torque_nm < 0.0) {
    throw std::invalid_argument("physics: a strapped weight's peak torque must be ≥ 0 N·m");
  }
  impl_->strapped_peak_torque_nm[wheel] = peak_torque_nm;
}

void RoverPhysics::hold_axle_tilt(std::size_t axle, std::optional<double> tilt_rad) {
  if (axle >= 2) throw std::out_of_range("physics: no exterior axle " + std::to_string(axle));
  if (tilt_rad && !std::isfinite(*tilt_rad)) {
    throw std::invalid_argument("physics: the axle's held tilt must be finite");
  }
  if (tilt_rad && !impl_->axle_hand_target_rad[axle]) {
    impl_->axle_hand_rad[axle] = impl_->data->qpos[impl_->ids.tilt_qpos[axle]];  // takes hold here
    impl_->axle_hand_speed_radps[axle] = 0.0;
  }
  impl_->axle_hand_target_rad[axle] = tilt_rad;
}

double RoverPhysics::time_s() const { return impl_->data->time; }
double RoverPhysics::timestep_s() const { return impl_->model->opt.timestep; }

void RoverPhysics::set_wheel_blocked(std::size_t wheel, bool blocked) {
  if (wheel >= kWheelCount) throw std::out_of_range("physics: no wheel " + std::to_string(wheel));
  mjModel& m = *impl_->model;
  const int constraint = impl_->ids.wheel_block[wheel];
  const int qpos = impl_->ids.shaft_qpos[wheel];
  // MuJoCo's joint equality holds q − q0 = polycoef[0]: hold the angle the wheel has now.
  m.eq_data[constraint * mjNEQDATA] = impl_->data->qpos[qpos] - m.qpos0[qpos];
  m.eq_active[constraint] = blocked ? 1 : 0;
}

void RoverPhysics::set_joint_jammed(std::size_t slot, bool jammed) {
  if (slot >= 2) throw std::out_of_range("physics: no joint " + std::to_string(slot));
  auto& jam = impl_->jammed_rad[slot];
  if (jammed == jam.has_value()) return;
  if (jammed) {
    const mjData& d = *impl_->data;
    jam = std::array<double, 2>{d.qpos[impl_->ids.joint_qpos[slot]],
                                d.qpos[impl_->ids.shaft_qpos[kJointMotors[slot]]]};
  } else {
    jam.reset();
  }
  impl_->apply_joint_mode(slot);
}

void RoverPhysics::set_wheel_contact(std::size_t wheel, bool has_contact) {
  if (wheel >= kWheelCount) throw std::out_of_range("physics: no wheel " + std::to_string(wheel));
  impl_->model->geom_contype[impl_->ids.wheel_geom[wheel]] = has_contact ? 1 : 0;
}

int RoverPhysics::mujoco_warning_count() const {
  int count = 0;
  for (const mjWarningStat& warning : impl_->data->warning) count += warning.number;
  return count;
}

}  // namespace marsokhod::sim
