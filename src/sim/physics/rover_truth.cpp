// What the simulator knows and no sensor does: pose, velocities, per-wheel slip and contact.
// The pose, joint angles and velocities are the state after the last step. What MuJoCo derives
// in its forward pass (contacts, wheel positions and slip, the accelerometer) belongs to the state
// at the start of the last step, one timestep older: recomputing it would double a step's cost.
#include <algorithm>
#include <cmath>

#include "sim/physics/rover_physics_impl.hpp"

namespace marsokhod::sim {
namespace {

using Vec3 = std::array<double, 3>;

Vec3 cross(const Vec3& u, const Vec3& v) {
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}
double dot(const Vec3& u, const Vec3& v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }

Vec3 roll_pitch_yaw(const mjtNum* q) {  // q = (w, x, y, z)
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const double sin_pitch = std::fmax(-1.0, std::fmin(1.0, 2.0 * (w * y - z * x)));
  return {std::atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y)), std::asin(sin_pitch),
          std::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))};
}

struct WheelContact {
  bool touching = false;
  Vec3 ground_normal{0.0, 0.0, 1.0};  // from the ground toward the wheel
};

std::array<WheelContact, kWheelCount> wheel_contacts(const mjData& data, const RoverModelIds& ids) {
  std::array<WheelContact, kWheelCount> contacts{};
  for (int i = 0; i < data.ncon; ++i) {
    const mjContact& contact = data.contact[i];
    for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
      const int geom = ids.wheel_geom[wheel];
      if ((contact.geom1 != geom && contact.geom2 != geom) || contacts[wheel].touching) continue;
      // MuJoCo's contact normal points from geom1 to geom2.
      const double sign = contact.geom2 == geom ? 1.0 : -1.0;
      contacts[wheel] = {
          true, {sign * contact.frame[0], sign * contact.frame[1], sign * contact.frame[2]}};
    }
  }
  return contacts;
}

// ω·r − v·h at the contact point: the contact point's velocity v_c = v + Ω × (−r·n), projected on
// the heading h = (axle × n)/|axle × n|, with its sign turned so that spinning in place is
// positive.
double wheel_slip_mps(const mjModel& model, const mjData& data, int body, const Vec3& normal,
                      double radius_m) {
  mjtNum velocity[6];  // world-oriented: angular, then linear at the wheel's center
  mj_objectVelocity(&model, &data, mjOBJ_BODY, body, velocity, 0);
  const mjtNum* rotation = data.xmat + 9 * body;
  const Vec3 axle{rotation[1], rotation[4], rotation[7]};  // the wheel's y axis in the world
  Vec3 heading = cross(axle, normal);
  const double length = std::sqrt(dot(heading, heading));
  if (length < 1e-9) return 0.0;  // the axle stands on its end: no heading
  for (double& component : heading) component /= length;
  const Vec3 omega{velocity[0], velocity[1], velocity[2]};
  const Vec3 rim =
      cross(omega, {-radius_m * normal[0], -radius_m * normal[1], -radius_m * normal[2]});
  const Vec3 contact_velocity{velocity[3] + rim[0], velocity[4] + rim[1], velocity[5] + rim[2]};
  return -dot(contact_velocity, heading);
}

}  // namespace

MotorVector RoverPhysics::shaft_angle_rad() const {
  MotorVector out{};
  for (std::size_t motor = 0; motor < kMotorCount; ++motor) {
    out[motor] = impl_->data->qpos[impl_->ids.shaft_qpos[motor]];
  }
  return out;
}

MotorVector RoverPhysics::shaft_velocity_radps() const {
  MotorVector out{};
  for (std::size_t motor = 0; motor < kMotorCount; ++motor) {
    out[motor] = impl_->data->qvel[impl_->ids.shaft_dof[motor]];
  }
  return out;
}

// The force MuJoCo's actuator applied in the last step: the speed–torque line, clipped at stall.
MotorVector RoverPhysics::shaft_torque_nm() const {
  MotorVector out{};
  for (std::size_t motor = 0; motor < kMotorCount; ++motor) {
    out[motor] = impl_->data->actuator_force[impl_->ids.motor_actuator[motor]];
  }
  // A joint shaft held back by its lock: the motor itself runs on its line near ω0, the lock
  // bears the rest.
  for (std::size_t slot = 0; slot < 2; ++slot) {
    if (!impl_->joint_overrun[slot]) continue;
    const std::size_t motor = slot == 0 ? kFrontJoint : kRearJoint;
    const MotorDrive& drive = impl_->drive;
    const double line = (drive.no_load_speed_radps[motor] -
                         impl_->data->qvel[impl_->ids.shaft_dof[motor]]) /
                        drive.droop_radps_per_nm[motor];
    out[motor] = std::clamp(line, -drive.stall_torque_nm[motor], drive.stall_torque_nm[motor]);
  }
  return out;
}

ImuTruth RoverPhysics::imu() const {
  const mjData& data = *impl_->data;
  const RoverModelIds& ids = impl_->ids;
  ImuTruth imu;
  // MuJoCo's accelerometer reads acceleration minus gravity; (3.5) reads gravity minus
  // acceleration.
  for (int i = 0; i < 3; ++i) imu.accel_mps2[i] = -data.sensordata[ids.accelerometer + i];
  imu.yaw_rate_radps = data.qvel[ids.free_dof + 5];
  imu.front_tilt_rad = data.qpos[ids.tilt_qpos[0]];
  imu.rear_tilt_rad = data.qpos[ids.tilt_qpos[1]];
  return imu;
}

GroundTruth RoverPhysics::truth() const {
  const mjModel& model = *impl_->model;
  const mjData& data = *impl_->data;
  const RoverModelIds& ids = impl_->ids;
  GroundTruth truth;
  const mjtNum* pose = data.qpos + ids.free_qpos;
  truth.position_m = {pose[0], pose[1], pose[2]};
  truth.roll_pitch_yaw_rad = roll_pitch_yaw(pose + 3);
  truth.velocity_mps = {data.qvel[ids.free_dof], data.qvel[ids.free_dof + 1],
                        data.qvel[ids.free_dof + 2]};
  truth.yaw_rate_radps = data.qvel[ids.free_dof + 5];
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    truth.joint_angle_rad[wheel] = data.qpos[ids.shaft_qpos[wheel]];
  }
  truth.joint_angle_rad[kFrontJoint] = data.qpos[ids.joint_qpos[0]];
  truth.joint_angle_rad[kRearJoint] = data.qpos[ids.joint_qpos[1]];
  for (std::size_t end = 0; end < 2; ++end) {
    truth.strut_angle_rad[end] = data.qpos[ids.strut_qpos[end]];
    truth.axle_tilt_rad[end] = data.qpos[ids.tilt_qpos[end]];
  }
  const auto contacts = wheel_contacts(data, ids);
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    const int body = ids.wheel_body[wheel];
    truth.wheel_contact[wheel] =
        contacts[wheel].touching || impl_->soil_wrenches[wheel].diagnostics.in_contact;
    truth.wheel_slip_mps[wheel] = wheel_slip_mps(model, data, body, contacts[wheel].ground_normal,
                                                 impl_->params.geometry.wheel_radius_m);
    truth.wheel_position_m[wheel] = {data.xpos[3 * body], data.xpos[3 * body + 1],
                                     data.xpos[3 * body + 2]};
  }
  return truth;
}

double RoverPhysics::total_mass_kg() const {
  double mass_kg = 0.0;
  for (int body = 0; body < impl_->model->nbody; ++body) mass_kg += impl_->model->body_mass[body];
  return mass_kg;
}

}  // namespace marsokhod::sim
