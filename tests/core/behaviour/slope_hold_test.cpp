#include "core/behaviour/slope_hold.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "behaviour_test_support.hpp"

namespace marsokhod::behaviour {
namespace {

using test::invalid_argument_message;
using test::kNaN;
using ::testing::HasSubstr;

constexpr double kTolerance = 1e-12;
constexpr double kPeriodS = 0.0156;  // the driver's cycle
constexpr double kUphillRad = 0.3;   // 17°, nose up (σ > 0)

BehaviourParams hold_params() {
  BehaviourParams params;
  params.slope_hold_gain_per_s = 10.0;  // K
  params.slope_hold_max_rad = 0.1;      // E
  params.slant_deadband_rad = 0.05;
  return params;
}

MotorVector all_wheels(double value) {
  MotorVector v{};
  for (std::size_t i = 0; i < kWheelCount; ++i) v[i] = value;
  return v;
}

// Nose up, an anchor planned to stand (ν̂ = 0) rolls back at −0.1 rad/s for ten cycles: it has
// lost 10·0.0156·0.1 = 0.0156 rad downhill, and the hold asks K·e = 0.156 rad/s forward (uphill).
TEST(SlopeHold, AWheelRollingBackDownhillIsAskedForwardByItsLostAngle) {
  SlopeHold hold;
  MotorVector term{};
  for (int k = 0; k < 10; ++k) {
    term = hold.update(all_wheels(-0.1), MotorVector{}, kUphillRad, true, kPeriodS, hold_params());
  }
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    EXPECT_NEAR(hold.lost_rad()[i], 0.0156, kTolerance) << i;
    EXPECT_NEAR(term[i], 0.156, kTolerance) << i;
  }
}

// Nose down (σ < 0) uphill is backward: a wheel carried forward past its plan has lost ground
// downhill, and the hold asks it backward.
TEST(SlopeHold, NoseDownTheHoldPushesBackward) {
  SlopeHold hold;
  const MotorVector term = hold.update(all_wheels(0.6), all_wheels(0.5), -kUphillRad, true,
                                       kPeriodS, hold_params());
  EXPECT_NEAR(hold.lost_rad()[kCenterLeft], 0.1 * kPeriodS, kTolerance);
  EXPECT_NEAR(term[kCenterLeft], -10.0 * 0.1 * kPeriodS, kTolerance);
}

// One-sided: a wheel ahead of its plan uphill, or turning as planned, is left to the open loop.
TEST(SlopeHold, AWheelAheadOfItsPlanUphillGetsNothing) {
  SlopeHold hold;
  MotorVector w = all_wheels(0.5);
  w[kFrontLeft] = 0.8;
  const MotorVector term = hold.update(w, all_wheels(0.5), kUphillRad, true, kPeriodS,
                                       hold_params());
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    EXPECT_EQ(term[i], 0.0) << i;
    EXPECT_EQ(hold.lost_rad()[i], 0.0) << i;
  }
}

// What the wheel catches up comes off its lost angle, down to 0, not below.
TEST(SlopeHold, CatchingUpGivesTheLostAngleBack) {
  SlopeHold hold;
  const BehaviourParams params = hold_params();
  hold.update(all_wheels(-0.2), MotorVector{}, kUphillRad, true, kPeriodS, params);  // e = 0.00312
  hold.update(all_wheels(0.1), MotorVector{}, kUphillRad, true, kPeriodS, params);   // − 0.00156
  EXPECT_NEAR(hold.lost_rad()[kBackRight], 0.1 * kPeriodS, kTolerance);
  const MotorVector term =
      hold.update(all_wheels(0.5), MotorVector{}, kUphillRad, true, kPeriodS, params);
  EXPECT_EQ(hold.lost_rad()[kBackRight], 0.0);
  EXPECT_EQ(term[kBackRight], 0.0);
}

// E bounds the count, K·E the request: 1 rad/s at the defaults however far the wheel went.
TEST(SlopeHold, TheRequestIsBoundedByKTimesE) {
  SlopeHold hold;
  MotorVector term{};
  for (int k = 0; k < 200; ++k) {
    term = hold.update(all_wheels(-1.0), MotorVector{}, kUphillRad, true, kPeriodS, hold_params());
  }
  EXPECT_EQ(hold.lost_rad()[kFrontRight], 0.1);
  EXPECT_NEAR(term[kFrontRight], 1.0, kTolerance);
}

// The spring: an open-loop motor gives way by B·τ under a torque τ (B⁺ = 0.030 rad/s per N·m
// of (4.7)), and ν̂ follows the command at once here. A wheel planned to stand that holds
// τ = 10 N·m downhill then turns at w = K·e − B·τ, and e settles where K·e = B·τ:
// e = 0.030·10/10 = 0.03 rad (3.75 mm at the rim of r = 0.125 m), the wheel standing.
TEST(SlopeHold, AHeldWheelSettlesWhereTheSpringCarriesTheLoad) {
  constexpr double kGiveRadpsPerNm = 0.030;
  constexpr double kTorqueNm = 10.0;
  SlopeHold hold;
  MotorVector term{};
  MotorVector w = all_wheels(-kGiveRadpsPerNm * kTorqueNm);  // open loop: 0.3 rad/s back
  for (int k = 0; k < 2000; ++k) {  // 31 s, two hundred time constants of 1/K
    term = hold.update(w, MotorVector{}, kUphillRad, true, kPeriodS, hold_params());
    for (std::size_t i = 0; i < kWheelCount; ++i) w[i] = term[i] - kGiveRadpsPerNm * kTorqueNm;
  }
  EXPECT_NEAR(hold.lost_rad()[kCenterRight], 0.03, 1e-9);
  EXPECT_NEAR(w[kCenterRight], 0.0, 1e-8);
}

// Gated: no gait, a slope inside the slant dead band, or K = 0, and the term is 0 and e forgotten.
TEST(SlopeHold, OffWithoutAGaitOnFlatGroundOrWithZeroGain) {
  const BehaviourParams params = hold_params();
  const auto lose_then = [&](double slope_rad, bool gait_running, const BehaviourParams& after) {
    SlopeHold hold;
    hold.update(all_wheels(-0.5), MotorVector{}, kUphillRad, true, kPeriodS, params);
    EXPECT_GT(hold.lost_rad()[kFrontLeft], 0.0);
    const MotorVector term =
        hold.update(all_wheels(-0.5), MotorVector{}, slope_rad, gait_running, kPeriodS, after);
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      EXPECT_EQ(term[i], 0.0) << i;
      EXPECT_EQ(hold.lost_rad()[i], 0.0) << i;
    }
  };
  lose_then(kUphillRad, false, params);
  lose_then(0.049, true, params);
  lose_then(-0.049, true, params);
  BehaviourParams off = params;
  off.slope_hold_gain_per_s = 0.0;
  lose_then(kUphillRad, true, off);
}

// The joints' entries are ignored, whatever they hold.
TEST(SlopeHold, TheJointsGetNothing) {
  SlopeHold hold;
  MotorVector w{};
  w[kFrontJoint] = -5.0;
  w[kRearJoint] = kNaN;
  const MotorVector term = hold.update(w, MotorVector{}, kUphillRad, true, kPeriodS, hold_params());
  EXPECT_EQ(term[kFrontJoint], 0.0);
  EXPECT_EQ(term[kRearJoint], 0.0);
}

TEST(SlopeHold, BadInputIsRejectedByNameAndTheStateKept) {
  SlopeHold hold;
  hold.update(all_wheels(-0.5), MotorVector{}, kUphillRad, true, kPeriodS, hold_params());
  const MotorVector before = hold.lost_rad();
  MotorVector w = all_wheels(-0.5);
  w[kCenterLeft] = kNaN;
  EXPECT_THAT(invalid_argument_message([&] {
                hold.update(w, MotorVector{}, kUphillRad, true, kPeriodS, hold_params());
              }),
              HasSubstr("velocity_radps[2]"));
  EXPECT_THAT(invalid_argument_message([&] {
                hold.update(all_wheels(0.0), MotorVector{}, kNaN, true, kPeriodS, hold_params());
              }),
              HasSubstr("slope_rad"));
  EXPECT_THAT(invalid_argument_message([&] {
                hold.update(all_wheels(0.0), MotorVector{}, kUphillRad, true, 0.0, hold_params());
              }),
              HasSubstr("period_s"));
  BehaviourParams negative = hold_params();
  negative.slope_hold_gain_per_s = -1.0;
  EXPECT_THAT(invalid_argument_message([&] {
                hold.update(all_wheels(0.0), MotorVector{}, kUphillRad, true, kPeriodS, negative);
              }),
              HasSubstr("slope_hold_gain_per_s"));
  EXPECT_EQ(hold.lost_rad(), before);
}

}  // namespace
}  // namespace marsokhod::behaviour
