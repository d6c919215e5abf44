// driver/joint_memory.hpp: a restarted driver continues from the kept joint state by chapter
// 3.2's increment and (4.1) along the way, and refuses registers that do not continue it.
#include "driver/joint_memory.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <numbers>

#include "core/adaptation/backlash.hpp"

namespace marsokhod::driver {
namespace {

constexpr double kCount = 2.0 * std::numbers::pi / 115000.0;  // rad per encoder pulse
constexpr double kGap = 0.05;                                  // a joint's backlash b [rad]

KeptJoint kept(std::uint16_t enc, std::uint16_t stp, bool dir, double shaft, double joint,
                double duty = 0.0) {
  return {{enc, stp, dir}, shaft, joint, duty};
}

std::optional<RestoredJoint> restore(const KeptJoint& k, tracking::EncoderReading now,
                                     std::string& why, const Params& params = Params{}) {
  return restore_joint(k, now, kGap, params, kFrontJoint, why);
}

// The shipped configuration's numbers: w = 2.827 rad/s, U up to 1.25·Ū, h = 0.0156 s, dog = 1
// (0.262144 s), max_duty_step 0.05, direction_change_duty 0.02; and dog = 4 (1.048576 s), the
// longest switch µ8 is configured with in the tests below.
constexpr double kW = 1.25 * 2.827;
constexpr double kDeadMan = 0.262144;

Params with_dog(std::uint8_t dog) {
  Params params;
  params.safety.dead_man_dog = dog;
  return params;
}

TEST(JointMemory, TheDutyLeftBoundsTheMovement) {
  const Params params;
  ASSERT_EQ(params.safety.dead_man_dog, 1);
  // At rest: a cycle at the step before it, and the rebound.
  const ShiftBounds rest = kept_joint_shift_bounds(params, 0.0);
  EXPECT_DOUBLE_EQ(rest.along_rad, kW * 0.05 * 2 * 0.0156 + kReboundRad);
  EXPECT_DOUBLE_EQ(rest.against_rad, rest.along_rad);
  // A gait's joint duty: the dead man's delay at d, the cycle before at d + step.
  const ShiftBounds slow = kept_joint_shift_bounds(params, -0.045);
  EXPECT_DOUBLE_EQ(slow.along_rad, kW * (0.045 * (kDeadMan + 0.0156) + 0.095 * 2 * 0.0156) + kReboundRad);
  EXPECT_DOUBLE_EQ(slow.against_rad, kW * 0.02 * 2 * 0.0156 + kReboundRad);
  // Four times the switch's delay: the part at d grows fourfold, the rest stays.
  const ShiftBounds slow4 = kept_joint_shift_bounds(with_dog(4), -0.045);
  EXPECT_DOUBLE_EQ(slow4.along_rad,
                   kW * (0.045 * (4 * kDeadMan + 0.0156) + 0.095 * 2 * 0.0156) + kReboundRad);
  EXPECT_DOUBLE_EQ(slow4.against_rad, slow.against_rad);
  // Fast: half the counter's range (32768 pulses) bounds it; so it does with the switch off.
  EXPECT_DOUBLE_EQ(kept_joint_shift_bounds(with_dog(4), 0.5).along_rad, 32768 * kCount);
  EXPECT_DOUBLE_EQ(kept_joint_shift_bounds(params, 0.5).along_rad,
                   kW * (0.5 * (kDeadMan + 0.0156) + 0.55 * 2 * 0.0156) + kReboundRad);
  EXPECT_DOUBLE_EQ(kept_joint_shift_bounds(with_dog(0), 0.0).along_rad, 32768 * kCount);
}

TEST(JointMemory, UnchangedRegistersGiveTheKeptState) {
  std::string why;
  const auto r = restore(kept(40000, 123, true, -1.6, -1.63), {40000, 123, true}, why);
  ASSERT_TRUE(r.has_value()) << why;
  EXPECT_EQ(r->shaft_rad, -1.6);
  EXPECT_EQ(r->joint_rad, -1.63);
  EXPECT_EQ(r->shift_rad, 0.0);
}

TEST(JointMemory, ShaftThatCoastedOnDragsTheJointAcrossItsGap) {
  // d = +0.05, dir = 0 (positive), 1500 pulses on while µ8's switch (dog = 4, 1.05 s) let it run:
  // 0.08195 rad. The shaft stood at the joint's negative end (p̄ = p), so it crosses the gap of
  // 0.05 rad and drags the joint by 0.08195 − 0.05 (4.1); the counter wraps on the way (65000 →
  // 964). With dog = 1 the same duty cannot have run that far, and the registers are refused.
  std::string why;
  EXPECT_FALSE(restore(kept(65000, 7, false, -1.5, -1.5, 0.05), {964, 7, false}, why).has_value());
  EXPECT_NE(why.find("more than it can at the duty 0.050"), std::string::npos) << why;
  const auto r = restore(kept(65000, 7, false, -1.5, -1.5, 0.05), {964, 7, false}, why, with_dog(4));
  ASSERT_TRUE(r.has_value()) << why;
  EXPECT_DOUBLE_EQ(r->shift_rad, 1500 * kCount);
  EXPECT_DOUBLE_EQ(r->shaft_rad, -1.5 + 1500 * kCount);
  EXPECT_DOUBLE_EQ(r->joint_rad, -1.5 + 1500 * kCount - kGap);
}

TEST(JointMemory, OneReversalIsFollowedThroughItsPoint) {
  // d = −0.05: negative (dir = 1) for 900 pulses to stp = 1100, then a rebound positive for 300
  // to enc = 1400: the shaft ends 600 pulses lower. Along the way (4.1): the first leg
  // (−0.0492 rad) pushes the joint down with it (the shaft starts at p, the negative end); the
  // rebound (+0.0164 rad) stays inside the gap, so the joint stays at the reversal point.
  std::string why;
  const auto r = restore(kept(200, 50, true, -2.0, -2.0, -0.05), {1400, 1100, false}, why);
  ASSERT_TRUE(r.has_value()) << why;
  EXPECT_DOUBLE_EQ(r->shift_rad, -600 * kCount);
  EXPECT_DOUBLE_EQ(r->shaft_rad, -2.0 - 600 * kCount);
  EXPECT_DOUBLE_EQ(r->joint_rad, -2.0 - 900 * kCount);
  const double p1 = adaptation::backlash_position(-2.0 - 900 * kCount, -2.0, kGap);
  EXPECT_DOUBLE_EQ(r->joint_rad, adaptation::backlash_position(r->shaft_rad, p1, kGap));
}

TEST(JointMemory, ChatterCountsInTheDirectionOfTheDuty) {
  // As the simulator's rear joint on seed 1: at d = −0.045 the shaft had just chattered a pulse
  // forward when its state was kept (dir = 0), went back to negative, ran 487 pulses to stp =
  // 1487 and rebounded 3 pulses (dir = 0 again) as µ8's switch stopped it: dir as kept, stp moved.
  // The 487 pulses count with the duty: −487 + 3.
  std::string why;
  const auto r = restore(kept(1000, 999, false, 1.3, 1.3, -0.045), {1490, 1487, false}, why);
  ASSERT_TRUE(r.has_value()) << why;
  EXPECT_DOUBLE_EQ(r->shift_rad, -484 * kCount);
  // The same registers with the duty the other way round: +487 + 3.
  const auto up = restore(kept(1000, 999, false, 1.3, 1.3, 0.045), {1490, 1487, false}, why);
  ASSERT_TRUE(up.has_value()) << why;
  EXPECT_DOUBLE_EQ(up->shift_rad, 490 * kCount);
  // At rest: the direction it reversed from last (negative, as it reverses to dir = 0).
  const auto rest = restore(kept(1000, 999, false, 1.3, 1.3, 0.0), {1010, 1007, false}, why);
  ASSERT_TRUE(rest.has_value()) << why;
  EXPECT_DOUBLE_EQ(rest->shift_rad, (-7 + 3) * kCount);
}

TEST(JointMemory, ARestartedControllerIsRefused) {
  // A controller reset while the driver was down reads stp = 0, dir = 0 and the pulses since
  // (none, at rest): the kept enc 31000 → 0 would be 34536 pulses.
  std::string why;
  EXPECT_FALSE(restore(kept(31000, 29000, false, -1.8, -1.8), {0, 0, false}, why).has_value());
  EXPECT_NE(why.find("µ6's shaft moved -1.8869 rad while the driver was down, more than it can at "
                     "the duty 0.000 it was left with (0.0075 rad)"),
            std::string::npos)
      << why;
}

TEST(JointMemory, AReversalOffTheArcIsRefused) {
  // stp = 5000 is not between the kept enc 100 and the new 400.
  std::string why;
  EXPECT_FALSE(restore(kept(100, 50, false, -1.8, -1.8), {400, 5000, true}, why).has_value());
  EXPECT_NE(why.find("µ6 reversed at stp 5000, off the arc from the kept enc 100 to enc 400"),
            std::string::npos)
      << why;
}

TEST(JointMemory, AMovementAgainstTheDutyIsRefused) {
  // d = +0.3 left, yet the shaft went 0.01 rad the other way: more than a cycle at 0.02 and the
  // rebound (0.0042 rad) allow.
  std::string why;
  EXPECT_FALSE(restore(kept(5000, 10, true, -1.8, -1.8, 0.3), {5183, 10, true}, why).has_value());
  EXPECT_NE(why.find("moved -0.0100 rad"), std::string::npos) << why;
  // The same movement with d = −0.3 is what that duty does.
  EXPECT_TRUE(restore(kept(5000, 10, true, -1.8, -1.8, -0.3), {5183, 10, true}, why).has_value());
}

TEST(JointMemory, ANonFiniteKeptPositionIsAnError) {
  std::string why;
  EXPECT_THROW(restore(kept(0, 0, false, std::numeric_limits<double>::quiet_NaN(), -1.8),
                       {0, 0, false}, why),
               std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::driver
