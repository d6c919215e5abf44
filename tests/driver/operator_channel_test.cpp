#include "driver/operator_channel.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace marsokhod::driver {
namespace {

OperatorInput targets(double v1) {
  OperatorInput in;
  in.targets = mobility::OperatorTargets{};
  in.targets->v1_radps = v1;
  return in;
}

TEST(OperatorChannel, NothingBeforeTheFirstInput) {
  const Params params;
  OperatorChannel channel(params);
  EXPECT_TRUE(channel.timed_out(0.0));
  EXPECT_EQ(channel.targets(0.0).v1_radps, 0.0);
}

TEST(OperatorChannel, TimeoutAfterHalfASecond) {
  // Field Experiment 6.7: more than 0.5 s without a command ⇒ stop.
  const Params params;
  OperatorChannel channel(params);
  ASSERT_FALSE(channel.receive(targets(1.0), 10.0));
  EXPECT_EQ(channel.targets(10.5).v1_radps, 1.0);
  EXPECT_FALSE(channel.timed_out(10.5));
  EXPECT_TRUE(channel.timed_out(10.5001));
  EXPECT_EQ(channel.targets(10.5001).v1_radps, 0.0);
}

TEST(OperatorChannel, InvalidInputIsRejectedAndTheLastValidOneStands) {
  const Params params;
  OperatorChannel channel(params);
  ASSERT_FALSE(channel.receive(targets(1.0), 1.0));
  const auto nan = channel.receive(targets(std::nan("")), 1.2);
  ASSERT_TRUE(nan);
  EXPECT_EQ(*nan, "v1 is not a finite number");
  const auto fast = channel.receive(targets(5.0), 1.3);
  ASSERT_TRUE(fast);
  EXPECT_NE(fast->find("v1: 5 is out of range"), std::string::npos) << *fast;
  EXPECT_NE(fast->find("\u22122.25..2.25"), std::string::npos) << *fast;
  EXPECT_EQ(channel.targets(1.4).v1_radps, 1.0);
  // Rejected inputs do not renew the timeout: 0.5 s after the last valid one it stops.
  EXPECT_TRUE(channel.timed_out(1.51));
}

TEST(OperatorChannel, GamepadAxisOutOfRangeIsRejected) {
  const Params params;
  OperatorChannel channel(params);
  OperatorInput in;
  in.gamepad = mobility::GamepadState{};
  in.gamepad->axes[1] = -1.5;
  const auto e = channel.receive(in, 0.0);
  ASSERT_TRUE(e);
  EXPECT_NE(e->find("axis 1"), std::string::npos) << *e;
}

OperatorInput stop_from(const std::string& reason) {
  OperatorInput stop;
  stop.stop = true;
  stop.stop_reason = reason;
  return stop;
}

TEST(OperatorChannel, StopHoldsWhileTheStickStaysPushed) {
  // The controller's console sends its reading at 20 Hz; a stop from another console must not
  // end with the next reading when the stick is still pushed.
  const Params params;
  OperatorChannel channel(params);
  ASSERT_FALSE(channel.receive(targets(1.0), 0.0));
  EXPECT_FALSE(channel.stop_latched());
  ASSERT_FALSE(channel.receive(stop_from("client 3 pressed STOP"), 0.1));
  EXPECT_TRUE(channel.stop_latched());
  EXPECT_EQ(channel.stop_reason(), "client 3 pressed STOP");
  for (int k = 1; k <= 20; ++k) {
    const double t = 0.1 + 0.05 * k;
    ASSERT_FALSE(channel.receive(targets(1.0), t));
    EXPECT_EQ(channel.targets(t).v1_radps, 0.0) << "at " << t << " s";
    EXPECT_TRUE(channel.stop_latched());
    // The pushed stick is the operator's input: no timeout, only the stop.
    EXPECT_FALSE(channel.timed_out(t));
  }
}

TEST(OperatorChannel, ANeutralInputReArms) {
  const Params params;
  OperatorChannel channel(params);
  ASSERT_FALSE(channel.receive(targets(1.0), 0.0));
  ASSERT_FALSE(channel.receive(stop_from(""), 0.1));
  EXPECT_EQ(channel.stop_reason(), "stop");
  ASSERT_FALSE(channel.receive(targets(0.5), 0.15));
  EXPECT_EQ(channel.targets(0.15).v1_radps, 0.0);
  ASSERT_FALSE(channel.receive(targets(0.0), 0.2));
  EXPECT_FALSE(channel.stop_latched());
  EXPECT_EQ(channel.stop_reason(), "stop");  // kept for the record
  ASSERT_FALSE(channel.receive(targets(0.5), 0.25));
  EXPECT_EQ(channel.targets(0.25).v1_radps, 0.5);
}

TEST(OperatorChannel, GaitSpeedAndJointButtonsAreNotNeutral) {
  const Params params;
  OperatorChannel channel(params);
  ASSERT_FALSE(channel.receive(stop_from("take-over"), 0.0));
  OperatorInput gait = targets(0.0);
  gait.targets->gait = mobility::Gait::kRolking;
  gait.targets->gait_speed = 0.3;
  ASSERT_FALSE(channel.receive(gait, 0.05));
  EXPECT_TRUE(channel.stop_latched());
  EXPECT_EQ(channel.targets(0.05).gait_speed, 0.0);
  EXPECT_EQ(channel.targets(0.05).gait, mobility::Gait::kRolking);  // the choice counts
  OperatorInput pad;
  pad.gamepad = mobility::GamepadState{};
  pad.gamepad->buttons[mobility::kLeftBumper] = true;  // contract the front joint
  ASSERT_FALSE(channel.receive(pad, 0.1));
  EXPECT_TRUE(channel.stop_latched());
  EXPECT_EQ(channel.targets(0.1).v6_radps, 0.0);
  pad.gamepad->buttons[mobility::kLeftBumper] = false;
  pad.gamepad->axes[mobility::kLeftStickY] = 0.05;  // inside the dead zone: centred
  ASSERT_FALSE(channel.receive(pad, 0.15));
  EXPECT_FALSE(channel.stop_latched());
}

TEST(OperatorChannel, IsNeutral) {
  mobility::OperatorTargets t;
  EXPECT_TRUE(is_neutral(t));
  t.gait = mobility::Gait::kWormLike;
  t.calibration_mode = true;
  EXPECT_TRUE(is_neutral(t));
  t.v7_radps = -0.1;
  EXPECT_FALSE(is_neutral(t));
  t.v7_radps = 0.0;
  t.rear_joint_target_rad = 0.2;
  EXPECT_FALSE(is_neutral(t));
}

}  // namespace
}  // namespace marsokhod::driver

namespace marsokhod::driver {
namespace {

// Issue #15: cmd_vel is a stream of targets; a mission is handed to the driver once; a heartbeat
// keeps what is in force alive and moves nothing itself.
TEST(OperatorChannel, VelocityBecomesV1AndV2AndObeysTheStopLatch) {
  const Params params;
  OperatorChannel channel(params);
  OperatorInput v;
  v.velocity = navigation::VelocityCommand{0.1, 0.2};
  ASSERT_FALSE(channel.receive(v, 1.0));
  EXPECT_NEAR(channel.targets(1.0).v1_radps, 0.8, 1e-12);   // 0.1/0.125
  EXPECT_NEAR(channel.targets(1.0).v2_radps, 0.56, 1e-12);  // 0.2·0.35/0.125
  EXPECT_TRUE(channel.velocity_in_force(1.0));
  OperatorInput beat;
  beat.heartbeat = true;
  ASSERT_FALSE(channel.receive(beat, 1.4));
  EXPECT_NEAR(channel.targets(1.8).v1_radps, 0.8, 1e-12);  // kept alive by the heartbeat
  EXPECT_FALSE(channel.velocity_in_force(1.9001));          // 0.5 s after the heartbeat
  OperatorInput stop;
  stop.stop = true;
  ASSERT_FALSE(channel.receive(stop, 2.0));
  ASSERT_FALSE(channel.receive(v, 2.1));  // still pushing: no re-arm
  EXPECT_EQ(channel.targets(2.1).v1_radps, 0.0);
  EXPECT_FALSE(channel.velocity_in_force(2.1));
  OperatorInput zero;
  zero.velocity = navigation::VelocityCommand{0.0, 0.0};
  ASSERT_FALSE(channel.receive(zero, 2.2));  // neutral: re-armed
  ASSERT_FALSE(channel.receive(v, 2.3));
  EXPECT_NEAR(channel.targets(2.3).v1_radps, 0.8, 1e-12);
  OperatorInput fast;
  fast.velocity = navigation::VelocityCommand{1.0, 0.0};
  EXPECT_TRUE(channel.receive(fast, 2.4));  // beyond 0.281 m/s: rejected, the last one stands
  EXPECT_NEAR(channel.targets(2.4).v1_radps, 0.8, 1e-12);
}

TEST(OperatorChannel, AMissionIsTakenOnceAndIsNeutral) {
  const Params params;
  OperatorChannel channel(params);
  ASSERT_FALSE(channel.receive(targets(1.0), 0.0));
  OperatorInput m;
  m.mission = navigation::MissionRequest{navigation::MissionKind::kMove, 0.0, 2.0, {}, {}};
  ASSERT_FALSE(channel.receive(m, 0.1));
  EXPECT_TRUE(is_neutral(channel.targets(0.1)));
  const auto taken = channel.take_mission();
  ASSERT_TRUE(taken);
  EXPECT_EQ(taken->distance_m, 2.0);
  EXPECT_FALSE(channel.take_mission());
  OperatorInput both = m;
  both.heartbeat = true;
  EXPECT_TRUE(channel.receive(both, 0.2));  // one command per input
  OperatorInput bad;
  bad.mission = navigation::MissionRequest{navigation::MissionKind::kTurn, 100.0, 0.0, {}, {}};
  const auto why = channel.receive(bad, 0.3);
  ASSERT_TRUE(why);
  EXPECT_NE(why->find("angle_rad"), std::string::npos);
  EXPECT_FALSE(channel.take_mission());
}

}  // namespace
}  // namespace marsokhod::driver
