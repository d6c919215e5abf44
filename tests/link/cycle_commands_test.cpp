// The rule that merges one cycle's console commands (cycle_commands.hpp): the newest input wins,
// except that a stop holds its cycle; a stop carries its reason; configures apply in order.
#include "link/cycle_commands.hpp"

#include <gtest/gtest.h>

namespace marsokhod::link {
namespace {

InboundCommand targets(double v1) {
  TargetsMessage message;
  message.targets.v1_radps = v1;
  return {1, message, ""};
}

InboundCommand stop(const std::string& reason) { return {2, StopMessage{}, reason}; }

InboundCommand configure(driver::SettingsChange change) {
  return {1, ConfigureMessage{change}, ""};
}

const driver::RuntimeSettings kCurrent{};

TEST(CycleCommands, NothingArrivedNothingChanges) {
  const CycleCommands merged = merge_cycle_commands({}, kCurrent);
  EXPECT_FALSE(merged.input);
  EXPECT_FALSE(merged.settings);
}

TEST(CycleCommands, TheNewestInputWins) {
  const CycleCommands merged = merge_cycle_commands({targets(0.5), targets(1.0)}, kCurrent);
  ASSERT_TRUE(merged.input && merged.input->targets);
  EXPECT_EQ(merged.input->targets->v1_radps, 1.0);
  EXPECT_FALSE(merged.settings);
}

TEST(CycleCommands, AStopHoldsItsCycleWithItsReason) {
  const CycleCommands merged = merge_cycle_commands(
      {targets(0.5), stop("client 2 pressed STOP"), targets(1.0)}, kCurrent);
  ASSERT_TRUE(merged.input);
  EXPECT_TRUE(merged.input->stop);
  EXPECT_FALSE(merged.input->targets);
  EXPECT_EQ(merged.input->stop_reason, "client 2 pressed STOP");
  // A later stop replaces an earlier one (its reason is the newest).
  const CycleCommands two = merge_cycle_commands({stop("first"), stop("second")}, kCurrent);
  EXPECT_EQ(two.input->stop_reason, "second");
}

TEST(CycleCommands, ClearFaultsIsAnInputPingAndControlAreNot) {
  const CycleCommands merged = merge_cycle_commands(
      {{1, ClearFaultsMessage{}, ""}, {1, PingMessage{}, ""}, {1, TakeControlMessage{}, ""}},
      kCurrent);
  ASSERT_TRUE(merged.input);
  EXPECT_TRUE(merged.input->clear_faults);
}

TEST(CycleCommands, ConfiguresApplyInOrderOnTheCurrentSettings) {
  driver::RuntimeSettings current;
  current.max_drop_v = 2.0;
  driver::SettingsChange first;
  first.speed_scale = 0.5;
  first.slant_response = false;
  driver::SettingsChange second;
  second.speed_scale = 0.25;
  const CycleCommands merged =
      merge_cycle_commands({configure(first), targets(1.0), configure(second)}, current);
  ASSERT_TRUE(merged.settings);
  EXPECT_EQ(merged.settings->speed_scale, 0.25);
  EXPECT_FALSE(merged.settings->switches.slant_response);
  EXPECT_EQ(merged.settings->max_drop_v, 2.0);
  ASSERT_TRUE(merged.input && merged.input->targets);  // a configure is no operator input
}

}  // namespace
}  // namespace marsokhod::link
