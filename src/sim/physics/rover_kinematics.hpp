// The rover's kinematic tree as the URDF gives it (rover_urdf.hpp): every joint with its parent
// and child link, its origin and axis, and where its value comes from in the simulator's ground
// truth. `marsokhod urdf` writes these joints; the live Foxglove link sends the transform of each
// (link_transforms) so that a 3-D view holding the URDF moves and bends the rover with the truth.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/params.hpp"
#include "sim/physics/rover_physics.hpp"

namespace marsokhod::sim {

using Vec3 = std::array<double, 3>;

struct RoverJoint {
  // Where the joint's value is read in GroundTruth.
  enum class Source { kMotor, kStrut, kTilt } source = Source::kMotor;
  std::size_t index = 0;  // kMotor: the motor (wheel angle, p6, p7); kStrut, kTilt: 0 front, 1 rear
  std::string name;
  std::string type;  // "continuous" or "revolute"
  std::string parent;
  std::string child;
  Vec3 xyz{};  // the origin in the parent link's frame
  Vec3 rpy{};
  Vec3 axis{};  // in the child's frame (a unit vector along x or y)
};

// In the URDF's order: the centre wheels, then per end the strut, the joint, the tilt and the
// exterior wheels. Throws std::invalid_argument for a geometry the levers cannot be built from.
std::vector<RoverJoint> rover_joints(const Params& params);

double joint_value(const RoverJoint& joint, const GroundTruth& truth);

// One link's pose in its parent's frame; rotation as a unit quaternion (x, y, z, w).
struct LinkTransform {
  std::string parent;
  std::string child;
  Vec3 translation{};
  std::array<double, 4> rotation{};
};

// R = Rz(yaw)·Ry(pitch)·Rx(roll) as (x, y, z, w): URDF's rpy, and the truth's roll_pitch_yaw_rad.
std::array<double, 4> quaternion_of_rpy(const Vec3& rpy);

// Each joint's transform at the truth's values: origin, then the rotation by the value about
// the axis (URDF's convention).
std::vector<LinkTransform> link_transforms(const std::vector<RoverJoint>& joints,
                                           const GroundTruth& truth);

}  // namespace marsokhod::sim
