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

TEST(ControlArbiter, AnyoneMayStopAndAnotherConsolesStopTakesControlAway) {
  ControlArbiter arbiter;
  arbiter.on_message(1, TakeControlMessage{});
  const ArbiterOutcome outcome = arbiter.on_message(2, StopMessage{});
  ASSERT_EQ(outcome.inbound.size(), 1U);
  EXPECT_TRUE(is_stop(outcome.inbound[0]));
  EXPECT_EQ(outcome.inbound[0].client_id, 2U);
  const std::string reason = "client 2 pressed STOP; client 1 lost control";
  EXPECT_EQ(outcome.inbound[0].reason, reason);
  EXPECT_FALSE(outcome.error.has_value());
  EXPECT_FALSE(arbiter.controller().has_value());
  ASSERT_TRUE(outcome.change.has_value());
  EXPECT_FALSE(outcome.change->controller.has_value());
  EXPECT_EQ(outcome.change->previous, 1U);
  EXPECT_EQ(outcome.change->reason, reason);
  ASSERT_TRUE(outcome.stopped.has_value());
  EXPECT_EQ(outcome.stopped->by, 2U);
  EXPECT_EQ(outcome.stopped->reason, reason);
  const ArbiterOutcome nobody = ControlArbiter().on_message(3, StopMessage{});
  ASSERT_EQ(nobody.inbound.size(), 1U);
  EXPECT_EQ(nobody.inbound[0].reason, "client 3 pressed STOP");
  EXPECT_FALSE(nobody.change.has_value());
}

TEST(ControlArbiter, TheControllersOwnStopKeepsControl) {
  ControlArbiter arbiter;
  arbiter.on_message(1, TakeControlMessage{});
  const ArbiterOutcome outcome = arbiter.on_message(1, StopMessage{});
  EXPECT_EQ(arbiter.controller(), 1U);
  EXPECT_FALSE(outcome.change.has_value());
  ASSERT_TRUE(outcome.stopped.has_value());
  EXPECT_EQ(outcome.stopped->reason, "client 1 pressed STOP");
}

TEST(ControlArbiter, EveryServerMadeStopIsNoticed) {
  ControlArbiter arbiter;
  EXPECT_EQ(arbiter.on_message(1, TakeControlMessage{}).stopped->reason, "client 1 took control");
  EXPECT_EQ(arbiter.on_message(1, ReleaseControlMessage{}).stopped->reason,
            "client 1 released control");
  arbiter.on_message(2, TakeControlMessage{});
  EXPECT_EQ(arbiter.on_disconnect(2).stopped->reason, "controller client 2 disconnected");
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
  EXPECT_TRUE(again.change_to_sender_only);  // a flood of these reaches nobody else
  EXPECT_FALSE(again.stopped.has_value());
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
