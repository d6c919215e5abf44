// The control rules: explicit take-over, read-only watchers, stop from anyone, a stop whenever
// control changes hands or is given up.
#include "link/control_arbiter.hpp"

#include <gtest/gtest.h>

namespace marsokhod::link {
namespace {

bool is_stop(const InboundCommand& command) {
  return std::holds_alternative<StopMessage>(command.message);
}

TEST(ControlArbiter, NobodyHoldsControlUntilSomeoneTakesIt) {
  ControlArbiter arbiter;
  EXPECT_FALSE(arbiter.controller().has_value());
  const ArbiterOutcome outcome = arbiter.on_message(1, GamepadMessage{});
  ASSERT_TRUE(outcome.error.has_value());
  EXPECT_EQ(outcome.error->field, "type");
  EXPECT_EQ(outcome.error->message, "read-only: take control first");
  EXPECT_TRUE(outcome.inbound.empty());
}

TEST(ControlArbiter, TakingControlStopsAndTellsEveryone) {
  ControlArbiter arbiter;
  const ArbiterOutcome outcome = arbiter.on_message(1, TakeControlMessage{});
  EXPECT_EQ(arbiter.controller(), 1U);
  ASSERT_EQ(outcome.inbound.size(), 2U);
  EXPECT_TRUE(std::holds_alternative<TakeControlMessage>(outcome.inbound[0].message));
  EXPECT_TRUE(is_stop(outcome.inbound[1]));
  EXPECT_EQ(outcome.inbound[1].reason, "client 1 took control");
  ASSERT_TRUE(outcome.change.has_value());
  EXPECT_EQ(outcome.change->controller, 1U);
  EXPECT_FALSE(outcome.change->previous.has_value());
}

TEST(ControlArbiter, TheControllerDrivesAndOthersOnlyWatch) {
  ControlArbiter arbiter;
  arbiter.on_message(1, TakeControlMessage{});
  for (const OperatorMessage& message :
       {OperatorMessage{GamepadMessage{}}, OperatorMessage{TargetsMessage{}},
        OperatorMessage{ConfigureMessage{}}, OperatorMessage{ClearFaultsMessage{}}}) {
    const ArbiterOutcome mine = arbiter.on_message(1, message);
    ASSERT_EQ(mine.inbound.size(), 1U) << message_type(message);
    EXPECT_EQ(mine.inbound[0].client_id, 1U);
    EXPECT_TRUE(mine.inbound[0].reason.empty());
    EXPECT_FALSE(mine.error.has_value());
    const ArbiterOutcome theirs = arbiter.on_message(2, message);
    EXPECT_TRUE(theirs.inbound.empty()) << message_type(message);
    ASSERT_TRUE(theirs.error.has_value());
    EXPECT_EQ(theirs.error->message, kReadOnlyMessage);
  }
  EXPECT_TRUE(arbiter.on_message(2, ReleaseControlMessage{}).error.has_value());
  EXPECT_EQ(arbiter.controller(), 1U);
}

TEST(ControlArbiter, AnyoneMayStop) {
  ControlArbiter arbiter;
  arbiter.on_message(1, TakeControlMessage{});
  const ArbiterOutcome outcome = arbiter.on_message(2, StopMessage{});
  ASSERT_EQ(outcome.inbound.size(), 1U);
  EXPECT_TRUE(is_stop(outcome.inbound[0]));
  EXPECT_EQ(outcome.inbound[0].client_id, 2U);
  EXPECT_FALSE(outcome.error.has_value());
  EXPECT_EQ(arbiter.controller(), 1U);
  EXPECT_EQ(ControlArbiter().on_message(3, StopMessage{}).inbound.size(), 1U);
}

TEST(ControlArbiter, TakingOverNamesThePreviousController) {
  ControlArbiter arbiter;
  arbiter.on_message(1, TakeControlMessage{});
  const ArbiterOutcome outcome = arbiter.on_message(2, TakeControlMessage{});
  EXPECT_EQ(arbiter.controller(), 2U);
  ASSERT_TRUE(outcome.change.has_value());
  EXPECT_EQ(outcome.change->previous, 1U);
  EXPECT_EQ(outcome.change->reason, "client 2 took control from client 1");
  ASSERT_EQ(outcome.inbound.size(), 2U);
  EXPECT_TRUE(is_stop(outcome.inbound[1]));
  EXPECT_TRUE(arbiter.on_message(1, GamepadMessage{}).error.has_value());
}

TEST(ControlArbiter, TakingControlAgainChangesNothing) {
  ControlArbiter arbiter;
  arbiter.on_message(1, TakeControlMessage{});
  const ArbiterOutcome again = arbiter.on_message(1, TakeControlMessage{});
  EXPECT_TRUE(again.inbound.empty());
  ASSERT_TRUE(again.change.has_value());
  EXPECT_EQ(again.change->controller, 1U);
  EXPECT_EQ(again.change->previous, 1U);
}

TEST(ControlArbiter, ReleasingStopsAndFreesControl) {
  ControlArbiter arbiter;
  arbiter.on_message(1, TakeControlMessage{});
  const ArbiterOutcome outcome = arbiter.on_message(1, ReleaseControlMessage{});
  EXPECT_FALSE(arbiter.controller().has_value());
  ASSERT_EQ(outcome.inbound.size(), 2U);
  EXPECT_TRUE(std::holds_alternative<ReleaseControlMessage>(outcome.inbound[0].message));
  EXPECT_TRUE(is_stop(outcome.inbound[1]));
  EXPECT_EQ(outcome.inbound[1].reason, "client 1 released control");
}

TEST(ControlArbiter, TheControllersDisconnectIsAStop) {
  ControlArbiter arbiter;
  arbiter.on_message(1, TakeControlMessage{});
  EXPECT_TRUE(arbiter.on_disconnect(2).inbound.empty());
  const ArbiterOutcome outcome = arbiter.on_disconnect(1);
  EXPECT_FALSE(arbiter.controller().has_value());
  ASSERT_EQ(outcome.inbound.size(), 1U);
  EXPECT_TRUE(is_stop(outcome.inbound[0]));
  EXPECT_EQ(outcome.inbound[0].client_id, 1U);
  EXPECT_EQ(outcome.inbound[0].reason, "controller client 1 disconnected");
  ASSERT_TRUE(outcome.change.has_value());
  EXPECT_FALSE(outcome.change->controller.has_value());
}

TEST(ControlArbiter, PingIsAnsweredNotForwarded) {
  ControlArbiter arbiter;
  const ArbiterOutcome outcome = arbiter.on_message(4, PingMessage{});
  EXPECT_TRUE(outcome.pong);
  EXPECT_TRUE(outcome.inbound.empty());
  EXPECT_FALSE(outcome.error.has_value());
}

}  // namespace
}  // namespace marsokhod::link
