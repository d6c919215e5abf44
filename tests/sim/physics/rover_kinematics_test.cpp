// The URDF's kinematic tree at the simulator's true joint values: composing every joint's
// transform from base_link (placed by the true pose) must land each wheel where MuJoCo has it —
// also with the joints bent and the rover on a slope, where struts and tilts are not zero.
#include "sim/physics/rover_kinematics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "physics_test_support.hpp"
#include "sim/physics/rover_mjcf.hpp"
#include "sim/physics/rover_urdf.hpp"

namespace marsokhod::sim {
namespace {

using Quaternion = std::array<double, 4>;  // x, y, z, w

Vec3 rotate(const Quaternion& q, const Vec3& v) {
  // v' = v + 2w(u × v) + 2u × (u × v), u = (x, y, z)
  const Vec3 u{q[0], q[1], q[2]};
  const auto cross = [](const Vec3& a, const Vec3& b) {
    return Vec3{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  };
  const Vec3 uv = cross(u, v);
  const Vec3 uuv = cross(u, uv);
  return {v[0] + 2 * (q[3] * uv[0] + uuv[0]), v[1] + 2 * (q[3] * uv[1] + uuv[1]),
          v[2] + 2 * (q[3] * uv[2] + uuv[2])};
}

Quaternion multiply(const Quaternion& a, const Quaternion& b) {
  return {a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
          a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
          a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
          a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]};
}

struct Pose {
  Vec3 position{};
  Quaternion rotation{0, 0, 0, 1};
};

// Every link's pose in the world: base_link at the true pose, then down the tree.
std::map<std::string, Pose> world_poses(const GroundTruth& truth,
                                        const std::vector<LinkTransform>& links) {
  std::map<std::string, Pose> poses;
  poses["base_link"] = {truth.position_m, quaternion_of_rpy(truth.roll_pitch_yaw_rad)};
  for (const LinkTransform& link : links) {  // parents come before their children
    const Pose& parent = poses.at(link.parent);
    const Vec3 offset = rotate(parent.rotation, link.translation);
    poses[link.child] = {{parent.position[0] + offset[0], parent.position[1] + offset[1],
                          parent.position[2] + offset[2]},
                         multiply(parent.rotation, link.rotation)};
  }
  return poses;
}

// MuJoCo's body positions are those its last step computed from the joint values before the
// step: compose from one step's truth and compare with the next step's positions.
void expect_wheels_where_mujoco_has_them(RoverPhysics& physics, const char* where) {
  const GroundTruth before = physics.truth();
  physics.step();
  const GroundTruth after = physics.truth();
  const auto poses = world_poses(before, link_transforms(rover_joints(Params{}), before));
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    const Pose& pose = poses.at(wheel_name(wheel));
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(pose.position[i], after.wheel_position_m[wheel][i], 1e-9)
          << where << ": " << wheel_name(wheel) << " axis " << i;
    }
  }
}

TEST(RoverKinematics, TheJointsAreTheUrdfsJoints) {
  const std::string urdf = rover_urdf(Params{});
  const auto joints = rover_joints(Params{});
  ASSERT_EQ(joints.size(), 12U);  // 6 wheels, 2 struts, 2 joint motors, 2 axle tilts
  for (const RoverJoint& j : joints) {
    const auto at = urdf.find("<joint name=\"" + j.name + "\" type=\"" + j.type + "\">");
    ASSERT_NE(at, std::string::npos) << j.name;
    const std::string element = urdf.substr(at, urdf.find("</joint>", at) - at);
    EXPECT_NE(element.find("<parent link=\"" + j.parent + "\"/>"), std::string::npos) << j.name;
    EXPECT_NE(element.find("<child link=\"" + j.child + "\"/>"), std::string::npos) << j.name;
  }
}

// At the layout's hinge value (p6 = −acos(a/b)) the lever hangs vertical from the joint, a above
// the center axle and √(b² − a²) ahead of it: the exterior axle is level with the center axle.
TEST(RoverKinematics, AtTheLayoutPoseTheExteriorAxleIsLevelWithTheCenterAxle) {
  const Params params;
  const double a = params.geometry.joint_to_exterior_axle_m;
  const double b = params.geometry.center_axle_to_joint_m;
  GroundTruth truth;
  truth.joint_angle_rad[kFrontJoint] = -std::acos(a / b);
  truth.joint_angle_rad[kRearJoint] = std::acos(a / b);
  const auto poses = world_poses(truth, link_transforms(rover_joints(params), truth));
  EXPECT_NEAR(poses.at("front_axle").position[0], std::sqrt(b * b - a * a), 1e-12);
  EXPECT_NEAR(poses.at("front_axle").position[2], 0.0, 1e-12);
  EXPECT_NEAR(poses.at("rear_axle").position[0], -std::sqrt(b * b - a * a), 1e-12);
  EXPECT_NEAR(poses.at("rear_axle").position[2], 0.0, 1e-12);
  EXPECT_NEAR(poses.at("wheel_FL").position[1], params.geometry.track_width_m / 2, 1e-12);
}

TEST(RoverKinematics, TheWheelsAreWhereMujocoHasThemAtRest) {
  RoverPhysics physics(Params{}, TerrainSpec{});
  testing::run(physics, 300);
  expect_wheels_where_mujoco_has_them(physics, "at rest");
}

TEST(RoverKinematics, TheWheelsAreWhereMujocoHasThemBentOnASlope) {
  RoverPhysics physics(Params{}, testing::slope_deg(10.0));
  testing::run(physics, 300);
  MotorVector speeds{};
  speeds[kFrontJoint] = -2.0;  // extend the front joint, contract the rear
  speeds[kRearJoint] = -1.0;
  physics.set_drive(testing::drive_at(speeds));  // the wheels held at 0
  testing::run(physics, 400);
  const GroundTruth truth = physics.truth();
  EXPECT_GT(std::abs(truth.joint_angle_rad[kFrontJoint] - (-1.2121)), 0.05);  // it did bend
  expect_wheels_where_mujoco_has_them(physics, "bending on a 10° slope");
}

}  // namespace
}  // namespace marsokhod::sim
