// parse_operator_message: every rejection names the field and says what is allowed; every message
// type survives operator_message_json → dump → parse unchanged.
#include "link/operator_message.hpp"

#include <gtest/gtest.h>

#include <string>

namespace marsokhod::link {
namespace {

using nlohmann::json;

const Params kParams{};  // max_drive 2.25, spin 1.5, trench 1.0, w = 2.827 rad/s

MessageError error_of(const std::string& text) {
  const ParseResult result = parse_operator_message(text, kParams);
  const auto* error = std::get_if<MessageError>(&result);
  if (error == nullptr) {
    ADD_FAILURE() << "accepted: " << text;
    return {};
  }
  return *error;
}

OperatorMessage message_from(const std::string& text) {
  const auto message = message_of(parse_operator_message(text, kParams));
  if (!message) {
    ADD_FAILURE() << "rejected: " << text << " — "
                  << std::get<MessageError>(parse_operator_message(text, kParams)).message;
    return PingMessage{};
  }
  return *message;
}

std::string gamepad_text(const std::string& axes, const std::string& buttons) {
  return R"({"type":"gamepad","seq":1,"sent_ms":0,"axes":)" + axes + R"(,"buttons":)" + buttons +
         "}";
}

const std::string kButtons =
    "[false,false,false,false,false,false,false,false,false,false,false,false,false,false,false,"
    "false,false]";

void expect_round_trip(const OperatorMessage& message) {
  const std::string text = operator_message_json(message).dump();
  const ParseResult parsed = parse_operator_message(text, kParams);
  const auto back = message_of(parsed);
  ASSERT_TRUE(back.has_value()) << text << " — " << std::get<MessageError>(parsed).message;
  EXPECT_EQ(*back, message) << text;
  EXPECT_EQ(message_type(*back), operator_message_json(message)["type"].get<std::string>());
}

TEST(OperatorMessage, ParsesAGamepadReading) {
  std::string buttons = kButtons;
  buttons.replace(1, 5, "true ");  // button 0 pressed
  const auto message = message_from(gamepad_text("[0, -1, 0.5, 1]", buttons));
  const auto& gamepad = std::get<GamepadMessage>(message);
  EXPECT_EQ(gamepad.reading.axes, (std::array<double, 4>{0.0, -1.0, 0.5, 1.0}));
  EXPECT_TRUE(gamepad.reading.buttons[0]);
  EXPECT_FALSE(gamepad.reading.buttons[16]);
}

TEST(OperatorMessage, RoundTripsEveryMessageType) {
  GamepadMessage gamepad;
  gamepad.reading.axes = {0.25, -1.0, 1.0, -0.125};
  gamepad.reading.buttons[mobility::kDpadUp] = true;
  gamepad.reading.buttons[mobility::kHome] = true;
  expect_round_trip(gamepad);
  gamepad.stamp = {9007199254740991U, 1.7e12 + 0.25};
  expect_round_trip(gamepad);
  expect_round_trip(TargetsMessage{{7, 12.5},
                                   {.v1_radps = 2.25, .v2_radps = -1.5, .v4_radps = 1.0,
                                    .v6_radps = 2.827, .v7_radps = -0.5,
                                    .gait = mobility::Gait::kRolkingExtendedBase,
                                    .gait_speed = -1.0, .calibration_mode = true,
                                    .joint_buttons = {}, .memory = {}}});
  expect_round_trip(TargetsMessage{});
  expect_round_trip(StopMessage{});
  expect_round_trip(ClearFaultsMessage{});
  expect_round_trip(TakeControlMessage{});
  expect_round_trip(ReleaseControlMessage{});
  expect_round_trip(PingMessage{});
  expect_round_trip(ConfigureMessage{});
  expect_round_trip(ConfigureMessage{{10.0, LoadDistributionMode::kSlip, false, true, false, true,
                                      0.0, SupplyKind::kTether}});
  ConfigureMessage partial;
  partial.change.slant_response = false;
  partial.change.speed_scale = 1.0;
  expect_round_trip(partial);
}

TEST(OperatorMessage, RoundTripsEveryGait) {
  for (const auto gait :
       {mobility::Gait::kNone, mobility::Gait::kRolking, mobility::Gait::kFrontWheelWalking,
        mobility::Gait::kRearWheelWalking, mobility::Gait::kWormLike,
        mobility::Gait::kRolkingExtendedBase}) {
    EXPECT_EQ(mobility::gait_from_id(mobility::gait_id(gait)), gait);
    TargetsMessage targets;
    targets.targets.gait = gait;
    expect_round_trip(targets);
  }
}

TEST(OperatorMessage, TargetsLeftOutAreZeroNoneAndFalse) {
  const auto message =
      message_from(R"({"type":"targets","seq":1,"sent_ms":0,"v2":-1.5,"gait":"worm-like"})");
  TargetsMessage expected;
  expected.stamp.seq = 1;
  expected.targets.v2_radps = -1.5;
  expected.targets.gait = mobility::Gait::kWormLike;
  EXPECT_EQ(std::get<TargetsMessage>(message), expected);
}

TEST(OperatorMessage, ConfigureKeysLeftOutStayUnset) {
  const auto message =
      message_from(R"({"type":"configure","behaviours":{"axle_placement":false},"max_drop_v":2})");
  ConfigureMessage expected;
  expected.change.axle_placement = false;
  expected.change.max_drop_v = 2.0;
  EXPECT_EQ(std::get<ConfigureMessage>(message), expected);
}

TEST(OperatorMessage, RejectsMalformedJsonAndNonObjects) {
  EXPECT_EQ(error_of(R"({"type":"stop")").field, "json");
  EXPECT_EQ(error_of("").field, "json");
  EXPECT_EQ(error_of(R"(["type","stop"])").field, "json");
  EXPECT_EQ(error_of("42").field, "json");
  EXPECT_EQ(error_of(R"({"type":"stop"} // comment)").field, "json");
  EXPECT_NE(error_of(R"({"type":"stop",})").message.find("malformed JSON"), std::string::npos);
}

TEST(OperatorMessage, RejectsNanAndInfinityLiteralsAsMalformed) {
  EXPECT_EQ(error_of(gamepad_text("[NaN, 0, 0, 0]", kButtons)).field, "json");
  EXPECT_EQ(error_of(gamepad_text("[Infinity, 0, 0, 0]", kButtons)).field, "json");
}

TEST(OperatorMessage, RejectsANumberBeyondDoublesRange) {
  const MessageError error = error_of(R"({"type":"targets","seq":1,"sent_ms":0,"v1":1e999})");
  EXPECT_EQ(error.field, "json");
  EXPECT_NE(error.message.find("overflow"), std::string::npos) << error.message;
  EXPECT_EQ(error_of(R"({"type":"targets","seq":1,"sent_ms":0,"v1":-1e400})").field, "json");
}

TEST(OperatorMessage, RejectsLargeIntegersAsOutOfRange) {
  EXPECT_EQ(error_of(R"({"type":"targets","seq":1,"sent_ms":0,"v1":18446744073709551616})").field, "v1");
  EXPECT_EQ(error_of(R"({"type":"configure","speed_scale":-9223372036854775808})").field,
            "speed_scale");
}

TEST(OperatorMessage, RejectsMissingOrUnknownTypes) {
  EXPECT_EQ(error_of(R"({"axes":[0,0,0,0]})").field, "type");
  EXPECT_EQ(error_of(R"({"type":7})").field, "type");
  const MessageError unknown = error_of(R"({"type":"launch"})");
  EXPECT_EQ(unknown.field, "type");
  EXPECT_NE(unknown.message.find("unknown message type \"launch\""), std::string::npos);
  EXPECT_NE(unknown.message.find("take_control"), std::string::npos) << unknown.message;
}

TEST(OperatorMessage, RejectsUnknownFieldsInEveryMessage) {
  EXPECT_EQ(error_of(R"({"type":"stop","now":true})").field, "now");
  EXPECT_EQ(error_of(R"({"type":"ping","t":1})").field, "t");
  EXPECT_EQ(error_of(R"({"type":"targets","seq":1,"sent_ms":0,"v5":0})").field, "v5");
  EXPECT_EQ(error_of(R"({"type":"configure","max_drop":1})").field, "max_drop");
  EXPECT_EQ(error_of(R"({"type":"configure","behaviours":{"gaits":true}})").field,
            "behaviours.gaits");
  EXPECT_EQ(error_of(gamepad_text("[0,0,0,0]", kButtons).insert(1, R"("id":1,)")).field, "id");
  const MessageError strange = error_of("{\"type\":\"stop\",\"a\\nb\":1}");
  EXPECT_EQ(strange.field, "\"a\\nb\"");  // quoted and escaped, never a raw control character
}

TEST(OperatorMessage, RejectsDuplicateKeys) {
  const MessageError error = error_of(R"({"type":"stop","type":"gamepad"})");
  EXPECT_EQ(error.field, "type");
  EXPECT_NE(error.message.find("twice"), std::string::npos);
  EXPECT_EQ(error_of(R"({"type":"configure","behaviours":{"slant_response":true,)"
                     R"("slant_response":false}})")
                .field,
            "slant_response");
}

TEST(OperatorMessage, NamesTheAxisOutOfRange) {
  const MessageError error = error_of(gamepad_text("[0, 1.7, 0, 0]", kButtons));
  EXPECT_EQ(error.field, "axes[1]");
  EXPECT_EQ(error.message, "axes[1]: 1.7 is out of range; allowed \u22121..1");
  EXPECT_EQ(error_of(gamepad_text("[0, 0, 0, -1.0001]", kButtons)).field, "axes[3]");
}

TEST(OperatorMessage, RejectsWrongGamepadShapesAndTypes) {
  EXPECT_EQ(error_of(gamepad_text("[0, 0, 0]", kButtons)).field, "axes");
  EXPECT_EQ(error_of(gamepad_text("[0, 0, 0, 0, 0]", kButtons)).field, "axes");
  EXPECT_EQ(error_of(gamepad_text("{\"0\":0}", kButtons)).field, "axes");
  EXPECT_EQ(error_of(gamepad_text("[0, \"0.5\", 0, 0]", kButtons)).field, "axes[1]");
  EXPECT_EQ(error_of(gamepad_text("[0, true, 0, 0]", kButtons)).field, "axes[1]");
  EXPECT_EQ(error_of(gamepad_text("[0, null, 0, 0]", kButtons)).message,
            "axes[1]: expected a number, got null");
  EXPECT_EQ(error_of(gamepad_text("[0, 0, 0, 0]", "[false]")).field, "buttons");
  std::string numeric = kButtons;
  numeric.replace(numeric.rfind("false"), 5, "1");  // the browser's value, not `pressed`
  const MessageError error = error_of(gamepad_text("[0, 0, 0, 0]", numeric));
  EXPECT_EQ(error.field, "buttons[16]");
  EXPECT_NE(error.message.find("expected true or false, got a number 1"), std::string::npos)
      << error.message;
  EXPECT_EQ(error_of(R"({"type":"gamepad","seq":1,"sent_ms":0,"buttons":[]})").field, "axes");
  EXPECT_EQ(error_of(R"({"type":"gamepad","seq":1,"sent_ms":0,"axes":[0,0,0,0]})").field,
            "buttons");
}

TEST(OperatorMessage, RejectsTargetsOutOfTheConfiguredRanges) {
  const MessageError v1 = error_of(R"({"type":"targets","seq":1,"sent_ms":0,"v1":2.3})");
  EXPECT_EQ(v1.field, "v1");
  EXPECT_EQ(v1.message, "v1: 2.3 is out of range; allowed \u22122.25..2.25 rad/s");
  EXPECT_EQ(error_of(R"({"type":"targets","seq":1,"sent_ms":0,"v2":-1.6})").field, "v2");
  EXPECT_EQ(error_of(R"({"type":"targets","seq":1,"sent_ms":0,"v4":1.01})").field, "v4");
  EXPECT_EQ(error_of(R"({"type":"targets","seq":1,"sent_ms":0,"v6":2.9})").field, "v6");
  EXPECT_EQ(error_of(R"({"type":"targets","seq":1,"sent_ms":0,"v7":-2.9})").field, "v7");
  EXPECT_EQ(error_of(R"({"type":"targets","seq":1,"sent_ms":0,"gait_speed":1.5})").field, "gait_speed");
  EXPECT_EQ(error_of(R"({"type":"targets","seq":1,"sent_ms":0,"v1":"fast"})").field, "v1");
  EXPECT_EQ(error_of(R"({"type":"targets","seq":1,"sent_ms":0,"calibration_mode":1})").field, "calibration_mode");
  EXPECT_EQ(error_of(R"({"type":"targets","seq":1,"sent_ms":0,"gait":3})").field, "gait");
  const MessageError gait = error_of(R"({"type":"targets","seq":1,"sent_ms":0,"gait":"front-wheel walking"})");
  EXPECT_EQ(gait.field, "gait");
  EXPECT_NE(gait.message.find("front-wheel-walking"), std::string::npos) << gait.message;
}

TEST(OperatorMessage, GamepadAndTargetsCarryASequenceNumberAndASendTime) {
  const auto message = message_from(R"({"type":"targets","seq":42,"sent_ms":1700000000123.5})");
  EXPECT_EQ(std::get<TargetsMessage>(message).stamp, (InputStamp{42, 1700000000123.5}));
  EXPECT_EQ(input_stamp(message), (InputStamp{42, 1700000000123.5}));
  EXPECT_FALSE(input_stamp(StopMessage{}).has_value());
  const MessageError missing = error_of(R"({"type":"targets","sent_ms":0})");
  EXPECT_EQ(missing.field, "seq");
  EXPECT_NE(missing.message.find("seq: missing"), std::string::npos) << missing.message;
  EXPECT_EQ(error_of(R"({"type":"targets","seq":1})").field, "sent_ms");
  EXPECT_EQ(error_of(R"({"type":"targets","seq":1.5,"sent_ms":0})").message,
            "seq: expected an integer, got 1.5");
  EXPECT_EQ(error_of(R"({"type":"targets","seq":-1,"sent_ms":0})").field, "seq");
  EXPECT_EQ(error_of(R"({"type":"targets","seq":9007199254740992,"sent_ms":0})").field, "seq");
  EXPECT_EQ(error_of(R"({"type":"targets","seq":"1","sent_ms":0})").field, "seq");
  EXPECT_EQ(error_of(R"({"type":"gamepad","seq":1,"sent_ms":-5,"axes":[0,0,0,0],"buttons":[]})")
                .field,
            "sent_ms");
  EXPECT_EQ(error_of(R"({"type":"stop","seq":1})").field, "seq");  // a stop is never stale
}

TEST(OperatorMessage, TargetRangesFollowTheParams) {
  Params fast;
  fast.operator_input.max_drive_speed_radps = 2.5;
  const std::string text = R"({"type":"targets","seq":1,"sent_ms":0,"v1":2.3})";
  EXPECT_TRUE(message_of(parse_operator_message(text, fast)).has_value());
  EXPECT_FALSE(message_of(parse_operator_message(text, kParams)).has_value());
}

TEST(OperatorMessage, RejectsConfigurationOutOfRange) {
  const MessageError zero = error_of(R"({"type":"configure","max_drop_v":0})");
  EXPECT_EQ(zero.field, "max_drop_v");
  EXPECT_EQ(zero.message, "max_drop_v: 0 is out of range; allowed (0, 10] V");
  EXPECT_EQ(error_of(R"({"type":"configure","max_drop_v":10.5})").field, "max_drop_v");
  EXPECT_EQ(error_of(R"({"type":"configure","speed_scale":-0.1})").field, "speed_scale");
  EXPECT_EQ(error_of(R"({"type":"configure","speed_scale":1.01})").field, "speed_scale");
  EXPECT_EQ(error_of(R"({"type":"configure","load_distribution":"h"})").field,
            "load_distribution");
  EXPECT_EQ(error_of(R"({"type":"configure","behaviours":true})").field, "behaviours");
  EXPECT_EQ(error_of(R"({"type":"configure","behaviours":{"power_management":"on"}})").field,
            "behaviours.power_management");
}

TEST(OperatorMessage, RejectsOversizedText) {
  const std::string text = R"({"type":"ping"})" + std::string(kMaxOperatorMessageBytes, ' ');
  const MessageError error = error_of(text);
  EXPECT_EQ(error.field, "json");
  EXPECT_NE(error.message.find("at most 8192"), std::string::npos);
}

TEST(OperatorMessage, MapsToTheDriversInput) {
  const auto gamepad = operator_input(message_from(gamepad_text("[0, -1, 0, 0]", kButtons)));
  ASSERT_TRUE(gamepad && gamepad->gamepad);
  EXPECT_EQ(gamepad->gamepad->axes[1], -1.0);
  const auto targets = operator_input(TargetsMessage{{},
                                                     {.v1_radps = 1.0, .v7_radps = 0.5,
                                                      .gait = mobility::Gait::kRolking,
                                                      .gait_speed = 0.25, .joint_buttons = {},
                                                      .memory = {}}});
  ASSERT_TRUE(targets && targets->targets);
  EXPECT_EQ(targets->targets->v1_radps, 1.0);
  EXPECT_EQ(targets->targets->v7_radps, 0.5);
  EXPECT_EQ(targets->targets->gait, mobility::Gait::kRolking);
  EXPECT_EQ(targets->targets->gait_speed, 0.25);
  EXPECT_TRUE(operator_input(StopMessage{})->stop);
  EXPECT_TRUE(operator_input(ClearFaultsMessage{})->clear_faults);
  EXPECT_FALSE(operator_input(PingMessage{}).has_value());
  EXPECT_FALSE(operator_input(ConfigureMessage{}).has_value());
}

}  // namespace
}  // namespace marsokhod::link

namespace marsokhod::link {
namespace {

// Issue #15's commands: cmd_vel, the missions and the heartbeat.
TEST(OperatorMessage, RoundTripsTheMissionsAndVelocity) {
  expect_round_trip(VelocityMessage{{3, 1.0}, {0.2, -0.5}});
  expect_round_trip(MissionMessage{{4, 2.0}, {navigation::MissionKind::kTurn, 1.5, 0.0, {}, {}}});
  expect_round_trip(MissionMessage{{5, 3.0}, {navigation::MissionKind::kMove, 0.0, -2.0, {}, {}}});
  expect_round_trip(MissionMessage{
      {6, 4.0}, {navigation::MissionKind::kGoto, 0.0, 0.0, {{2.0, 0.0}, {2.0, 2.0}, {-1.5, 0.25}}, {}}});
  expect_round_trip(MissionMessage{
      {8, 6.0}, {navigation::MissionKind::kGoto, 0.0, 0.0, {{2.0, 0.0}}, 9.0}});
  expect_round_trip(MissionMessage{{9, 7.0}, {navigation::MissionKind::kTurn, -0.5, 0.0, {}, 0.5}});
  expect_round_trip(HeartbeatMessage{{7, 5.0}});
  const auto goto_message = message_from(
      R"({"type":"mission","seq":1,"sent_ms":0,"kind":"goto","waypoints":[{"x_m":2,"y_m":0},{"x_m":2,"y_m":2}]})");
  const auto input = operator_input(goto_message);
  ASSERT_TRUE(input && input->mission);
  ASSERT_EQ(input->mission->waypoints.size(), 2U);
  EXPECT_EQ(input->mission->waypoints[1].y_m, 2.0);
  EXPECT_TRUE(operator_input(HeartbeatMessage{})->heartbeat);
  EXPECT_EQ(operator_input(VelocityMessage{{1, 0}, {0.1, 0.2}})->velocity->yaw_radps, 0.2);
}

TEST(OperatorMessage, RejectsBadMissionsAndVelocitiesNamingTheField) {
  EXPECT_EQ(error_of(R"({"type":"velocity","seq":1,"sent_ms":0,"v_mps":0.5,"yaw_radps":0})").field,
            "v_mps");  // beyond r·v1ᵈ = 0.281 m/s
  EXPECT_EQ(error_of(R"({"type":"velocity","seq":1,"sent_ms":0,"v_mps":0.1})").field, "yaw_radps");
  EXPECT_EQ(error_of(R"({"type":"mission","seq":1,"sent_ms":0,"kind":"fly"})").field, "kind");
  EXPECT_EQ(error_of(R"({"type":"mission","seq":1,"sent_ms":0,"kind":"turn"})").field, "angle_rad");
  EXPECT_EQ(
      error_of(R"({"type":"mission","seq":1,"sent_ms":0,"kind":"turn","angle_rad":1,"distance_m":2})")
          .field,
      "distance_m");
  EXPECT_EQ(error_of(R"({"type":"mission","seq":1,"sent_ms":0,"kind":"goto","waypoints":[]})").field,
            "waypoints");
  EXPECT_EQ(
      error_of(R"({"type":"mission","seq":1,"sent_ms":0,"kind":"goto","waypoints":[{"x_m":1}]})")
          .field,
      "waypoints[0].y_m");
  EXPECT_EQ(error_of(R"({"type":"mission","seq":1,"sent_ms":0,"kind":"move","distance_m":1000})")
                .field,
            "distance_m");
  // A mission's own standing: 0 < settle_s ≤ 60 s, a number.
  const auto stood = operator_input(message_from(
      R"({"type":"mission","seq":1,"sent_ms":0,"kind":"move","distance_m":1,"settle_s":9})"));
  ASSERT_TRUE(stood && stood->mission);
  EXPECT_EQ(stood->mission->settle_s, 9.0);
  const auto plain = operator_input(message_from(
      R"({"type":"mission","seq":1,"sent_ms":0,"kind":"move","distance_m":1})"));
  ASSERT_TRUE(plain && plain->mission);
  EXPECT_FALSE(plain->mission->settle_s.has_value());
  for (const char* bad : {"0", "-1", "61", "\"9\"", "null"}) {
    const MessageError error = error_of(
        std::string(R"({"type":"mission","seq":1,"sent_ms":0,"kind":"move","distance_m":1,)") +
        R"("settle_s":)" + bad + "}");
    EXPECT_EQ(error.field, "settle_s") << bad;
    EXPECT_NE(error.message.find("settle_s"), std::string::npos) << error.message;
  }
  EXPECT_EQ(error_of(R"({"type":"heartbeat","seq":1,"sent_ms":0,"v1":0})").field, "v1");
  EXPECT_EQ(error_of(R"({"type":"heartbeat"})").field, "seq");
}

}  // namespace
}  // namespace marsokhod::link
