// Foxglove's WebSocket protocol as the link speaks it: the binary messages byte by byte (the
// spec's layout), the JSON ones' fields, the client's operations read strictly (every malformed
// one an error naming what is wrong), and the run-time settings as parameters, round trip.
#include "link/foxglove_protocol.hpp"

#include <gtest/gtest.h>

#include "link/command_json.hpp"

namespace marsokhod::link::foxglove {
namespace {

using Json = nlohmann::json;

std::string error_of(std::string_view text) {
  const ClientOp op = parse_client_op(text);
  const auto* error = std::get_if<FoxgloveError>(&op);
  return error != nullptr ? error->message : "(no error)";
}

TEST(FoxgloveProtocol, MessageDataIsOpcodeSubscriptionTimeAndPayloadLittleEndian) {
  const std::string data = message_data(0x04030201U, 0x0102030405060708ULL, "{\"a\":1}");
  const std::string expected = std::string("\x01\x01\x02\x03\x04\x08\x07\x06\x05\x04\x03\x02\x01", 13) +
                               "{\"a\":1}";
  EXPECT_EQ(data, expected);
}

TEST(FoxgloveProtocol, TimeIsOpcodeTwoAndNanosecondsLittleEndian) {
  // 12.5 s of mission time = 12 500 000 000 ns = 0x2_E90E_DD00.
  EXPECT_EQ(time_message(12'500'000'000ULL),
            std::string("\x02\x00\xDD\x0E\xE9\x02\x00\x00\x00", 9));
}

TEST(FoxgloveProtocol, ServerInfoAdvertisesTimeAndParameters) {
  const Json info = server_info_json("marsokhod");
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_EQ(info["name"], "marsokhod");
  EXPECT_EQ(info["capabilities"], Json({"time", "parameters", "parametersSubscribe"}));
}

TEST(FoxgloveProtocol, AdvertiseCarriesTheJsonSchema) {
  const Json a = advertise_json({{3, "/imu", "marsokhod.imu", R"({"type":"object"})"}});
  EXPECT_EQ(a["op"], "advertise");
  ASSERT_EQ(a["channels"].size(), 1U);
  const Json& c = a["channels"][0];
  EXPECT_EQ(c["id"], 3);
  EXPECT_EQ(c["topic"], "/imu");
  EXPECT_EQ(c["encoding"], "json");
  EXPECT_EQ(c["schemaName"], "marsokhod.imu");
  EXPECT_EQ(c["schemaEncoding"], "jsonschema");
  EXPECT_EQ(c["schema"], R"({"type":"object"})");
  EXPECT_EQ(status_message(StatusLevel::kError, "x"),
            Json({{"op", "status"}, {"level", 2}, {"message", "x"}}));
  EXPECT_EQ(parameter_values_json(Json::array(), "q1")["id"], "q1");
  EXPECT_FALSE(parameter_values_json(Json::array()).contains("id"));
}

TEST(FoxgloveProtocol, ReadsTheClientsOperations) {
  const ClientOp subscribe =
      parse_client_op(R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":4},{"id":9,"channelId":1}]})");
  ASSERT_TRUE(std::holds_alternative<Subscribe>(subscribe));
  EXPECT_EQ(std::get<Subscribe>(subscribe).subscriptions,
            (std::vector<std::pair<std::uint32_t, std::uint32_t>>{{0, 4}, {9, 1}}));
  const ClientOp unsubscribe = parse_client_op(R"({"op":"unsubscribe","subscriptionIds":[9]})");
  EXPECT_EQ(std::get<Unsubscribe>(unsubscribe).subscription_ids, std::vector<std::uint32_t>{9});
  const ClientOp get = parse_client_op(R"({"op":"getParameters","parameterNames":["speed_scale"],"id":"r1"})");
  EXPECT_EQ(std::get<GetParameters>(get).names, std::vector<std::string>{"speed_scale"});
  EXPECT_EQ(std::get<GetParameters>(get).id, "r1");
  const ClientOp set =
      parse_client_op(R"({"op":"setParameters","parameters":[{"name":"speed_scale","value":0.5}]})");
  EXPECT_EQ(std::get<SetParameters>(set).parameters.size(), 1U);
  EXPECT_FALSE(std::get<SetParameters>(set).id.has_value());
  EXPECT_TRUE(std::holds_alternative<SubscribeParameterUpdates>(
      parse_client_op(R"({"op":"subscribeParameterUpdates","parameterNames":[]})")));
  EXPECT_TRUE(std::holds_alternative<UnsubscribeParameterUpdates>(
      parse_client_op(R"({"op":"unsubscribeParameterUpdates","parameterNames":["max_drop_v"]})")));
}

TEST(FoxgloveProtocol, MalformedOperationsAreErrorsNamingWhatIsWrong) {
  EXPECT_NE(error_of("{\"op\":").find("malformed JSON"), std::string::npos) << error_of("{\"op\":");
  EXPECT_NE(error_of("[1,2]").find("expected a JSON object"), std::string::npos);
  EXPECT_EQ(error_of(R"({"subscriptions":[]})"), "op: missing");
  EXPECT_NE(error_of(R"({"op":"advertise","channels":[]})").find("\"advertise\" is not supported"),
            std::string::npos);
  EXPECT_EQ(error_of(R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":1}]})"),
            "subscribe: subscriptions[0].id: expected a whole number 0..4294967295, got -1");
  EXPECT_EQ(error_of(R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":4294967296}]})"),
            "subscribe: subscriptions[0].channelId: expected a whole number 0..4294967295, got "
            "4294967296");
  EXPECT_EQ(error_of(R"({"op":"subscribe","subscriptions":[{"id":1.5,"channelId":1}]})"),
            "subscribe: subscriptions[0].id: expected a whole number 0..4294967295, got 1.5");
  EXPECT_EQ(error_of(R"({"op":"subscribe","subscriptions":[{"id":1}]})"),
            "subscribe: channelId: missing");
  EXPECT_EQ(error_of(R"({"op":"unsubscribe","subscriptionIds":"all"})"),
            "unsubscribe: subscriptionIds: expected an array, got \"all\"");
  EXPECT_NE(error_of(R"({"op":"subscribe","subscriptions":[],"extra":1})").find("extra"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMaxClientMessageBytes + 1, ' ')).find("at most 65536"),
            std::string::npos);
}

driver::RuntimeSettings unusual_settings() {
  driver::RuntimeSettings s;
  s.max_drop_v = 2.25;
  s.speed_scale = 0.5;
  s.switches.load_distribution = LoadDistributionMode::kVariance;
  s.switches.power_management = false;
  s.switches.slant_response = true;
  s.switches.contract_on_turn = false;
  s.switches.axle_placement = true;
  s.supply = SupplyKind::kTether;
  return s;
}

TEST(FoxgloveProtocol, TheSettingsAreParametersUnderConfiguresKeys) {
  const Json parameters = settings_parameters(runtime_settings_json(unusual_settings()));
  ASSERT_EQ(parameters.size(), 8U);
  std::map<std::string, Json> by_name;
  for (const Json& p : parameters) by_name[p["name"]] = p;
  EXPECT_EQ(by_name.at("max_drop_v")["value"], 2.25);
  EXPECT_EQ(by_name.at("max_drop_v")["type"], "float64");
  EXPECT_EQ(by_name.at("speed_scale")["value"], 0.5);
  EXPECT_EQ(by_name.at("load_distribution")["value"], "v");
  EXPECT_FALSE(by_name.at("load_distribution").contains("type"));
  EXPECT_EQ(by_name.at("supply")["value"], "tether");
  EXPECT_EQ(by_name.at("behaviours.power_management")["value"], false);
  EXPECT_EQ(by_name.at("behaviours.axle_placement")["value"], true);
}

TEST(FoxgloveProtocol, SetParametersIsTheConsolesConfigureRoundTrip) {
  const Json parameters = settings_parameters(runtime_settings_json(unusual_settings()));
  const auto configure = configure_of(parameters, Params{});
  ASSERT_TRUE(std::holds_alternative<ConfigureMessage>(configure));
  EXPECT_EQ(std::get<ConfigureMessage>(configure).change.applied_to(driver::RuntimeSettings{}),
            unusual_settings());
  // One parameter changes one setting; the others stay as they are.
  const auto one = configure_of(Json::parse(R"([{"name":"behaviours.slant_response","value":false}])"),
                                Params{});
  const driver::RuntimeSettings changed =
      std::get<ConfigureMessage>(one).change.applied_to(unusual_settings());
  EXPECT_FALSE(changed.switches.slant_response);
  EXPECT_EQ(changed.max_drop_v, 2.25);
}

TEST(FoxgloveProtocol, SetParametersIsCheckedAsTheConsolesConfigureIs) {
  const auto error = [](const char* parameters) {
    const auto result = configure_of(Json::parse(parameters), Params{});
    const auto* e = std::get_if<FoxgloveError>(&result);
    return e != nullptr ? e->message : "(accepted)";
  };
  EXPECT_EQ(error(R"([{"name":"max_drop_v","value":0}])"),
            "setParameters: max_drop_v: 0 is out of range; allowed (0, 10] V");
  EXPECT_EQ(error(R"([{"name":"speed_scale","value":"fast"}])").rfind("setParameters: speed_scale", 0), 0U);
  EXPECT_NE(error(R"([{"name":"launch","value":1}])").find("launch"), std::string::npos);
  EXPECT_NE(error(R"([{"name":"behaviours.fly","value":true}])").find("fly"), std::string::npos);
  EXPECT_NE(error(R"([{"name":"type","value":"stop"}])").find("not a setting"), std::string::npos);
  EXPECT_NE(error(R"([{"name":"max_drop_v","value":1},{"name":"max_drop_v","value":2}])")
                .find("twice"),
            std::string::npos);
  EXPECT_NE(error(R"([{"value":1}])").find("parameters[0]"), std::string::npos);
}

}  // namespace
}  // namespace marsokhod::link::foxglove
