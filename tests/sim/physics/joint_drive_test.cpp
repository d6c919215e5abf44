#include "sim/physics/joint_drive.hpp"

#include <gtest/gtest.h>

namespace marsokhod::sim {
namespace {

TEST(BacklashPosition, Example42) {
  EXPECT_DOUBLE_EQ(backlash_position(2.75, 3, 1), 2.75);
  EXPECT_DOUBLE_EQ(backlash_position(3.25, 3, 1), 3.0);
  EXPECT_DOUBLE_EQ(backlash_position(4.25, 3, 1), 3.25);
  EXPECT_DOUBLE_EQ(backlash_position(4.25, 3, 0), 4.25);  // b = 0: P = p̄
}

TEST(JointDrive, StartsLockedAtTheGapsLowerEnd) {
  const JointDrive drive(1.2121, 0.25);
  EXPECT_EQ(drive.mode(), JointMode::kLocked);
  EXPECT_DOUBLE_EQ(drive.held_angle_rad(), 1.2121);
}

TEST(JointDrive, PushesDownAtOnceButUpOnlyAcrossTheGap) {
  JointDrive down(1.2121, 0.25);
  EXPECT_TRUE(down.update(1.2121, 1.2121, -0.5));  // already on the lower end
  EXPECT_EQ(down.mode(), JointMode::kPushingDown);
  EXPECT_DOUBLE_EQ(down.coupling_offset_rad(), 0.0);

  JointDrive up(1.2121, 0.25);
  EXPECT_FALSE(up.update(1.2121, 1.2121, 0.5));  // the shaft turns freely in the gap
  EXPECT_FALSE(up.update(1.2121 + 0.2499, 1.2121, 0.5));
  EXPECT_EQ(up.mode(), JointMode::kLocked);
  EXPECT_TRUE(up.update(1.2121 + 0.25, 1.2121, 0.5));
  EXPECT_EQ(up.mode(), JointMode::kPushingUp);
  EXPECT_DOUBLE_EQ(up.coupling_offset_rad(), -0.25);
}

TEST(JointDrive, LocksWhereTheJointIsWhenTheCommandStopsOrReverses) {
  JointDrive drive(1.2121, 0.25);
  drive.update(1.4621, 1.2121, 0.5);
  drive.update(1.7, 1.45, 0.5);
  EXPECT_DOUBLE_EQ(drive.held_angle_rad(), 1.45);  // the furthest angle reached
  EXPECT_TRUE(drive.update(1.71, 1.46, 0.0));
  EXPECT_EQ(drive.mode(), JointMode::kLocked);
  EXPECT_DOUBLE_EQ(drive.held_angle_rad(), 1.46);
  // Reversing: the shaft must first cross the gap back to the lower end.
  EXPECT_FALSE(drive.update(1.71, 1.46, -0.5));
  EXPECT_EQ(drive.mode(), JointMode::kLocked);
  EXPECT_TRUE(drive.update(1.46, 1.46, -0.5));
  EXPECT_EQ(drive.mode(), JointMode::kPushingDown);
}

// The lock holds the joint softly: under load it may creep a fraction of a milliradian from the
// held angle, while the shaft's stops stay at the held angle (and p + b). A shaft on its stop
// still engages: the gap is measured from the held angle, not from the crept joint.
TEST(JointDrive, EngagesAtTheStopEvenWhenTheLockedJointCrept) {
  JointDrive down(-1.21811, 0.052);
  EXPECT_TRUE(down.update(-1.21811, -1.21823, -0.3));
  EXPECT_EQ(down.mode(), JointMode::kPushingDown);
  JointDrive up(1.2121, 0.25);
  EXPECT_TRUE(up.update(1.2121 + 0.25, 1.2123, 0.3));
  EXPECT_EQ(up.mode(), JointMode::kPushingUp);
}

TEST(JointDrive, TheRatchetNeverRetreats) {
  JointDrive drive(-1.2121, 0.052);
  drive.update(-1.2121, -1.2121, -0.5);
  drive.update(-1.30, -1.30, -0.5);
  drive.update(-1.29, -1.29, -0.5);  // pushed back by a load: the held angle stays
  EXPECT_DOUBLE_EQ(drive.held_angle_rad(), -1.30);
}

TEST(JointDrive, ZeroBacklashEngagesEitherWay) {
  JointDrive drive(0.0, 0.0);
  EXPECT_TRUE(drive.update(0.0, 0.0, 0.1));
  EXPECT_EQ(drive.mode(), JointMode::kPushingUp);
  EXPECT_TRUE(drive.update(0.0, 0.0, -0.1));
  EXPECT_EQ(drive.mode(), JointMode::kPushingDown);
}

}  // namespace
}  // namespace marsokhod::sim
