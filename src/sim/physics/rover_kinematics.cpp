#include "sim/physics/rover_kinematics.hpp"

#include <cmath>

#include "sim/physics/chassis_geometry.hpp"
#include "sim/physics/rover_mjcf.hpp"

namespace marsokhod::sim {
namespace {

using Quaternion = std::array<double, 4>;  // x, y, z, w

Quaternion multiply(const Quaternion& a, const Quaternion& b) {
  return {a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
          a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
          a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
          a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]};
}

Quaternion about_axis(const Vec3& axis, double angle_rad) {
  const double s = std::sin(angle_rad / 2);
  return {axis[0] * s, axis[1] * s, axis[2] * s, std::cos(angle_rad / 2)};
}

constexpr Vec3 kAxisX{1.0, 0.0, 0.0};
constexpr Vec3 kAxisY{0.0, 1.0, 0.0};

RoverJoint wheel_joint(std::size_t wheel, const std::string& parent, double lateral_m) {
  return {RoverJoint::Source::kMotor, wheel, wheel_name(wheel), "continuous", parent,
          wheel_name(wheel), {0.0, lateral_m, 0.0}, {}, kAxisY};
}

}  // namespace

std::array<double, 4> quaternion_of_rpy(const Vec3& rpy) {
  const double cr = std::cos(rpy[0] / 2), sr = std::sin(rpy[0] / 2);
  const double cp = std::cos(rpy[1] / 2), sp = std::sin(rpy[1] / 2);
  const double cy = std::cos(rpy[2] / 2), sy = std::sin(rpy[2] / 2);
  return {sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy,
          cr * cp * cy + sr * sp * sy};
}

std::vector<RoverJoint> rover_joints(const Params& params) {
  const GeometryParams& g = params.geometry;
  validate_geometry(g);
  const double half_track = g.track_width_m / 2;
  std::vector<RoverJoint> joints = {wheel_joint(kCenterLeft, "base_link", half_track),
                                    wheel_joint(kCenterRight, "base_link", -half_track)};
  for (const bool front : {true, false}) {
    const std::string prefix = front ? "front" : "rear";
    const std::size_t end = front ? 0 : 1;
    const double a = g.joint_to_exterior_axle_m;
    const double b = g.center_axle_to_joint_m;
    const double reach = (front ? 1.0 : -1.0) * std::sqrt(b * b - a * a);
    // The layout's hinge value (MuJoCo's ref): the joint's origin turns back by it, so that the
    // joint's value is the hinge's (p6, p7).
    const double ref = (front ? -1.0 : 1.0) * vertical_bend_rad(g);
    const std::size_t motor = front ? kFrontJoint : kRearJoint;
    joints.push_back({RoverJoint::Source::kStrut, end, "strut_" + prefix, "revolute", "base_link",
                      prefix + "_strut", {}, {}, kAxisY});
    joints.push_back({RoverJoint::Source::kMotor, motor, joint_hinge_name(motor), "revolute",
                      prefix + "_strut", prefix + "_lever", {reach, 0.0, a}, {0.0, -ref, 0.0},
                      kAxisY});
    joints.push_back({RoverJoint::Source::kTilt, end, front ? kFrontTiltName : kRearTiltName,
                      "revolute", prefix + "_lever", prefix + "_axle", {0.0, 0.0, -a}, {}, kAxisX});
    joints.push_back(wheel_joint(front ? kFrontLeft : kBackLeft, prefix + "_axle", half_track));
    joints.push_back(wheel_joint(front ? kFrontRight : kBackRight, prefix + "_axle", -half_track));
  }
  return joints;
}

double joint_value(const RoverJoint& joint, const GroundTruth& truth) {
  switch (joint.source) {
    case RoverJoint::Source::kMotor:
      return truth.joint_angle_rad.at(joint.index);
    case RoverJoint::Source::kStrut:
      return truth.strut_angle_rad.at(joint.index);
    case RoverJoint::Source::kTilt:
      return truth.axle_tilt_rad.at(joint.index);
  }
  return 0.0;
}

std::vector<LinkTransform> link_transforms(const std::vector<RoverJoint>& joints,
                                           const GroundTruth& truth) {
  std::vector<LinkTransform> out;
  out.reserve(joints.size());
  for (const RoverJoint& joint : joints) {
    out.push_back({joint.parent, joint.child, joint.xyz,
                   multiply(quaternion_of_rpy(joint.rpy),
                            about_axis(joint.axis, joint_value(joint, truth)))});
  }
  return out;
}

}  // namespace marsokhod::sim
