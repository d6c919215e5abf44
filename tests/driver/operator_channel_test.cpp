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
  EXPECT_NE(fast->find("v1 = 5.0"), std::string::npos) << *fast;
  EXPECT_NE(fast->find("±2.25"), std::string::npos) << *fast;
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

TEST(OperatorChannel, StopZeroesUntilTheNextInput) {
  const Params params;
  OperatorChannel channel(params);
  ASSERT_FALSE(channel.receive(targets(1.0), 0.0));
  OperatorInput stop;
  stop.stop = true;
  ASSERT_FALSE(channel.receive(stop, 0.1));
  EXPECT_EQ(channel.targets(0.2).v1_radps, 0.0);
  EXPECT_FALSE(channel.timed_out(0.2));
  ASSERT_FALSE(channel.receive(targets(0.5), 0.3));
  EXPECT_EQ(channel.targets(0.3).v1_radps, 0.5);
}

}  // namespace
}  // namespace marsokhod::driver
