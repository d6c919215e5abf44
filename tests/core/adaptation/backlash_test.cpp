#include "core/adaptation/backlash.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "adaptation_test_util.hpp"

namespace marsokhod::adaptation {
namespace {

using test::invalid_argument_message;
using test::kInf;
using test::kNaN;
using ::testing::HasSubstr;

constexpr double kTolerance = 1e-12;

// Example 4.2, b = 1, p = 3: the shaft free in [3, 4].
TEST(Backlash, Example4_2ShaftBelowTheGapDragsTheJointDown) {
  EXPECT_EQ(backlash_position(2.75, 3.0, 1.0), 2.75);
  EXPECT_EQ(backlash_factor_positive(2.75, 3.0, 1.0), 0.0);
  EXPECT_EQ(backlash_factor_negative(2.75, 3.0, 1.0), 1.0);
}

TEST(Backlash, Example4_2ShaftInsideTheGapLeavesTheJoint) {
  EXPECT_EQ(backlash_position(3.25, 3.0, 1.0), 3.0);
  EXPECT_EQ(backlash_factor_positive(3.25, 3.0, 1.0), 0.25);
  EXPECT_EQ(backlash_factor_negative(3.25, 3.0, 1.0), 0.75);
}

TEST(Backlash, Example4_2ShaftAboveTheGapDragsTheJointUp) {
  EXPECT_EQ(backlash_position(4.25, 3.0, 1.0), 3.25);
  EXPECT_EQ(backlash_factor_positive(4.25, 3.0, 1.0), 1.0);
  EXPECT_EQ(backlash_factor_negative(4.25, 3.0, 1.0), 0.0);
}

TEST(Backlash, GapEndsBelongToTheGap) {
  EXPECT_EQ(backlash_position(3.0, 3.0, 1.0), 3.0);  // p = P(p, p, b), Procedure 4.3
  EXPECT_EQ(backlash_position(4.0, 3.0, 1.0), 3.0);
  EXPECT_EQ(backlash_factor_positive(3.0, 3.0, 1.0), 0.0);
  EXPECT_EQ(backlash_factor_positive(4.0, 3.0, 1.0), 1.0);
}

TEST(Backlash, WithoutPlayTheJointFollowsTheShaft) {
  EXPECT_EQ(backlash_position(2.75, 3.0, 0.0), 2.75);
  EXPECT_EQ(backlash_position(4.25, 3.0, 0.0), 4.25);
  EXPECT_EQ(backlash_factor_positive(2.75, 3.0, 0.0), 1.0);
  EXPECT_EQ(backlash_factor_negative(4.25, 3.0, 0.0), 1.0);
  EXPECT_EQ(backlash_velocity(2.75, -0.5, 3.0, 0.0), -0.5);
}

// (4.2): w = w̄ P^(sgn w̄); at p̄ = 3.25 in [3, 4], P⁺ = 0.25 and P⁻ = 0.75.
TEST(Backlash, VelocityTakesTheFactorOfItsDirection) {
  EXPECT_EQ(backlash_velocity(3.25, 2.0, 3.0, 1.0), 0.5);
  EXPECT_EQ(backlash_velocity(3.25, -2.0, 3.0, 1.0), -1.5);
  EXPECT_EQ(backlash_velocity(3.25, 0.0, 3.0, 1.0), 0.0);
}

TEST(Backlash, NonFiniteOrNegativeArgumentsAreRejectedByName) {
  EXPECT_THAT(invalid_argument_message([] { backlash_position(kNaN, 3.0, 1.0); }),
              HasSubstr("backlash_position: motor_position_rad = nan"));
  EXPECT_THAT(invalid_argument_message([] { backlash_factor_positive(3.0, kInf, 1.0); }),
              HasSubstr("joint_position_rad = inf"));
  EXPECT_THAT(invalid_argument_message([] { backlash_factor_negative(3.0, 3.0, -0.1); }),
              HasSubstr("backlash_rad = -0.1"));
  EXPECT_THAT(invalid_argument_message([] { backlash_velocity(3.0, kNaN, 3.0, 1.0); }),
              HasSubstr("motor_velocity_radps = nan"));
}

// Procedure 4.3 / Remark 3.1: the joints start at the negative end of their gap, p⁰ = p̄⁰.
TEST(BacklashTracker, StartsAtTheInitialPositionsOfRemark3_1) {
  const RoverBacklashTracker tracker(MotorParams{});
  const MotorVector position = tracker.joint_position_rad();
  EXPECT_EQ(position[kFrontJoint], -1.2121);
  EXPECT_EQ(position[kRearJoint], 1.2121);
  EXPECT_EQ(position[kFrontLeft], 0.0);
  EXPECT_EQ(tracker.joint_velocity_radps(), MotorVector{});
  EXPECT_EQ(tracker.motor(kRearJoint).backlash_rad(), 0.250);
  EXPECT_EQ(tracker.motor(kFrontJoint).backlash_rad(), 0.052);
}

// Rear joint, b = 0.25, from p = p̄ = 1.2121 with w̄ = ±1 rad/s, worked by hand:
//   p̄ = 1.3121: inside [1.2121, 1.4621], p stays, w = 1 · 0.1/0.25 = 0.4
//   p̄ = 1.4121: p stays, w = 0.2/0.25 = 0.8
//   p̄ = 1.5121: past the top end, p = 1.5121 − 0.25 = 1.2621, w = 1 · P⁺(…, p = 1.2121) = 1
//   p̄ = 1.4121, w̄ = −1: inside [1.2621, 1.5121], p stays, P⁺ = 0.15/0.25 = 0.6, w = −0.4
TEST(BacklashTracker, RearJointCrossesItsGapThenReverses) {
  BacklashTracker rear(0.25, 1.2121);
  rear.update(1.3121, 1.0);
  EXPECT_EQ(rear.joint_position_rad(), 1.2121);
  EXPECT_NEAR(rear.joint_velocity_radps(), 0.4, kTolerance);
  rear.update(1.4121, 1.0);
  EXPECT_EQ(rear.joint_position_rad(), 1.2121);
  EXPECT_NEAR(rear.joint_velocity_radps(), 0.8, kTolerance);
  rear.update(1.5121, 1.0);
  EXPECT_NEAR(rear.joint_position_rad(), 1.2621, kTolerance);
  EXPECT_EQ(rear.joint_velocity_radps(), 1.0);
  rear.update(1.4121, -1.0);
  EXPECT_NEAR(rear.joint_position_rad(), 1.2621, kTolerance);
  EXPECT_NEAR(rear.joint_velocity_radps(), -0.4, kTolerance);
}

TEST(BacklashTracker, ResetRepeatsProcedure4_3) {
  BacklashTracker front(0.052, -1.2121);
  front.update(-1.0, 2.0);
  front.reset(-1.5);
  EXPECT_EQ(front.joint_position_rad(), -1.5);
  EXPECT_EQ(front.joint_velocity_radps(), 0.0);
}

TEST(BacklashTracker, RejectsNonFiniteInputAndKeepsItsState) {
  EXPECT_THAT(invalid_argument_message([] { BacklashTracker(-0.1, 0.0); }),
              HasSubstr("backlash_rad"));
  BacklashTracker rear(0.25, 1.2121);
  rear.update(1.5121, 1.0);
  EXPECT_THROW(rear.update(kNaN, 1.0), std::invalid_argument);
  EXPECT_THROW(rear.update(1.6, kInf), std::invalid_argument);
  EXPECT_NEAR(rear.joint_position_rad(), 1.2621, kTolerance);
  EXPECT_EQ(rear.joint_velocity_radps(), 1.0);
}

TEST(RoverBacklashTracker, WheelsFollowTheirMotorsExactly) {
  RoverBacklashTracker tracker(MotorParams{});
  const MotorVector position{0.1, -0.2, 0.3, -0.4, 0.5, -0.6, -1.2121, 1.2121};
  const MotorVector velocity{1.0, -1.0, 2.0, -2.0, 0.5, -0.5, 0.0, 0.0};
  tracker.update(position, velocity);
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    EXPECT_EQ(tracker.joint_position_rad()[i], position[i]) << kMotorNames[i];
    EXPECT_EQ(tracker.joint_velocity_radps()[i], velocity[i]) << kMotorNames[i];
  }
}

TEST(RoverBacklashTracker, RejectsTheWholeUpdateNamingTheMotor) {
  RoverBacklashTracker tracker(MotorParams{});
  MotorVector position{0.1, 0.1, 0.1, 0.1, 0.1, 0.1, -1.0, kNaN};
  EXPECT_THAT(invalid_argument_message([&] { tracker.update(position, MotorVector{}); }),
              HasSubstr("motor_position_rad[7] = nan"));
  EXPECT_EQ(tracker.joint_position_rad(), MotorParams{}.initial_position_rad);
  MotorVector backlash{};
  backlash[kFrontJoint] = -0.052;
  EXPECT_THAT(invalid_argument_message([&] { RoverBacklashTracker(backlash, MotorVector{}); }),
              HasSubstr("backlash_rad[6]"));
  EXPECT_THAT(invalid_argument_message([&] { tracker.reset(position); }),
              HasSubstr("initial_position_rad[7]"));
}

// A random walk of the shaft with steps up to 2b, starting inside the gap.
class BacklashWalk : public ::testing::TestWithParam<double> {};

TEST_P(BacklashWalk, TheShaftStaysInsideTheGapAfterEveryUpdate) {
  const double backlash_rad = GetParam();
  std::mt19937 random(42);
  std::uniform_real_distribution<double> step(-2.0 * backlash_rad - 0.01,
                                              2.0 * backlash_rad + 0.01);
  double motor_rad = 0.3 * backlash_rad;
  BacklashTracker tracker(backlash_rad, 0.0);
  for (int k = 0; k < 10000; ++k) {
    const double motor_step_rad = step(random);
    motor_rad += motor_step_rad;
    const double joint_before_rad = tracker.joint_position_rad();
    tracker.update(motor_rad, motor_step_rad / 0.0156);
    const double joint_rad = tracker.joint_position_rad();
    ASSERT_LE(joint_rad, motor_rad + kTolerance) << "k = " << k;
    ASSERT_LE(motor_rad, joint_rad + backlash_rad + kTolerance) << "k = " << k;
    // The joint never outruns the shaft, and the velocity factor lies in [0, 1].
    ASSERT_LE(std::abs(joint_rad - joint_before_rad), std::abs(motor_step_rad) + kTolerance);
    ASSERT_LE(std::abs(tracker.joint_velocity_radps()), std::abs(motor_step_rad / 0.0156));
    ASSERT_GE(tracker.joint_velocity_radps() * motor_step_rad, 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(FrontRearAndExample, BacklashWalk, ::testing::Values(0.052, 0.25, 1.0));

TEST(BacklashProperties, NoPlayIsTheIdentityOverARandomSequence) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> value(-10.0, 10.0);
  BacklashTracker wheel(0.0, 0.0);
  for (int k = 0; k < 1000; ++k) {
    const double motor_rad = value(random);
    const double motor_radps = value(random);
    wheel.update(motor_rad, motor_radps);
    ASSERT_EQ(wheel.joint_position_rad(), motor_rad);
    ASSERT_EQ(wheel.joint_velocity_radps(), motor_radps);
  }
}

TEST(BacklashProperties, AMotorReversingInsideTheGapLeavesTheJointStill) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> fraction(0.0, 1.0);
  constexpr double kRearBacklashRad = 0.25;
  BacklashTracker rear(kRearBacklashRad, 1.2121);
  for (int k = 0; k < 1000; ++k) {
    // Anywhere in [p, p + b], in either direction, as long as the shaft does not leave the gap.
    const double motor_rad = 1.2121 + kRearBacklashRad * fraction(random);
    rear.update(motor_rad, fraction(random) - 0.5);
    ASSERT_EQ(rear.joint_position_rad(), 1.2121) << "k = " << k;
  }
}

}  // namespace
}  // namespace marsokhod::adaptation
