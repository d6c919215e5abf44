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

// Composed with rotation matrices, independently of the library's quaternion arithmetic.
using Matrix = std::array<std::array<double, 3>, 3>;

Matrix matrix_of(const std::array<double, 4>& q) {  // (x, y, z, w), unit
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  return {{{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
           {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
           {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}}};
}

Matrix times(const Matrix& a, const Matrix& b) {
  Matrix c{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 3; ++k) c[i][j] += a[i][k] * b[k][j];
    }
  }
  return c;
}

Vec3 times(const Matrix& a, const Vec3& v) {
  return {a[0][0] * v[0] + a[0][1] * v[1] + a[0][2] * v[2],
          a[1][0] * v[0] + a[1][1] * v[1] + a[1][2] * v[2],
          a[2][0] * v[0] + a[2][1] * v[1] + a[2][2] * v[2]};
}

// R = Rz(yaw)·Ry(pitch)·Rx(roll), the truth's convention, as a product of the three matrices.
Matrix matrix_of_rpy(const Vec3& rpy) {
  const double cr = std::cos(rpy[0]), sr = std::sin(rpy[0]);
  const double cp = std::cos(rpy[1]), sp = std::sin(rpy[1]);
  const double cy = std::cos(rpy[2]), sy = std::sin(rpy[2]);
  const Matrix rx{{{1, 0, 0}, {0, cr, -sr}, {0, sr, cr}}};
  const Matrix ry{{{cp, 0, sp}, {0, 1, 0}, {-sp, 0, cp}}};
  const Matrix rz{{{cy, -sy, 0}, {sy, cy, 0}, {0, 0, 1}}};
  return times(rz, times(ry, rx));
}

struct Pose {
  Vec3 position{};
  Matrix rotation{};
};

// Every link's pose in the world: base_link at the true pose, then down the tree.
std::map<std::string, Pose> world_poses(const GroundTruth& truth,
                                        const std::vector<LinkTransform>& links) {
  std::map<std::string, Pose> poses;
  poses["base_link"] = {truth.position_m, matrix_of_rpy(truth.roll_pitch_yaw_rad)};
  for (const LinkTransform& link : links) {  // parents come before their children
    const Pose& parent = poses.at(link.parent);
    const Vec3 offset = times(parent.rotation, link.translation);
    poses[link.child] = {{parent.position[0] + offset[0], parent.position[1] + offset[1],
                          parent.position[2] + offset[2]},
                         times(parent.rotation, matrix_of(link.rotation))};
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
