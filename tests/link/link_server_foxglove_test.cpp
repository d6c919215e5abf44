// The server's Foxglove WebSocket (/foxglove, foxglove.websocket.v1) on loopback with a real
// WebSocket client: the subprotocol, the token in the query and the Origin rule, serverInfo,
// channels advertised as they appear, subscribe/unsubscribe and the binary message data, errors
// as status messages that leave the connection (and everyone else's) standing, the parameters
// (read by anyone, set only by the holder of control), and a slow client losing old data instead
// of its connection. Every wait has a deadline (test_client.hpp).
#include <gtest/gtest.h>

#include <cstring>
#include <thread>

#include "link/foxglove_protocol.hpp"
#include "link/link_server.hpp"
#include "test_client.hpp"

namespace marsokhod::link {
namespace {

using namespace std::chrono_literals;
using Json = nlohmann::json;
using testing::TestClient;

constexpr const char* kToken = "foxglove-token-0123456789";
const std::string kSubprotocol(foxglove::kSubprotocol);

// A message data frame taken apart.
struct Data {
  std::uint8_t opcode = 0;
  std::uint32_t subscription = 0;
  std::uint64_t time_ns = 0;
  std::string payload;
};

Data parse_binary(const std::string& bytes) {
  Data d;
  d.opcode = static_cast<std::uint8_t>(bytes.at(0));
  const auto le = [&](std::size_t at, int n) {
    std::uint64_t v = 0;
    for (int i = n - 1; i >= 0; --i) v = (v << 8) | static_cast<std::uint8_t>(bytes.at(at + i));
    return v;
  };
  if (d.opcode == foxglove::kTimeOpcode) {
    d.time_ns = le(1, 8);
  } else {
    d.subscription = static_cast<std::uint32_t>(le(1, 4));
    d.time_ns = le(5, 8);
    d.payload = bytes.substr(13);
  }
  return d;
}

class FoxgloveServerTest : public ::testing::Test {
 protected:
  void start(ServerOptions options = {}) {
    options.listen = {"127.0.0.1", 0};
    options.token = kToken;
    options.auth_backoff_first_s = 1e-6;  // a wrong token's back-off is over by the next connect
    server_ = std::make_unique<LinkServer>(Params{}, std::move(options));
    server_->start();
  }
  std::unique_ptr<TestClient> open(const std::string& query = std::string("?token=") + kToken,
                                   testing::Headers headers = {{"Sec-WebSocket-Protocol",
                                                                kSubprotocol}}) {
    return std::make_unique<TestClient>(server_->port(), "/foxglove" + query, headers);
  }
  // The next text message with op `op`, skipping binary messages and other ops.
  static std::optional<Json> next_op(TestClient& client, const std::string& op) {
    const auto deadline = std::chrono::steady_clock::now() + testing::kWait;
    while (std::chrono::steady_clock::now() < deadline) {
      const auto frame = client.receive_frame(std::chrono::duration_cast<std::chrono::milliseconds>(
          deadline - std::chrono::steady_clock::now()));
      if (!frame) return std::nullopt;
      if (frame->binary) continue;
      Json message = Json::parse(frame->data);
      if (message["op"] == op) return message;
    }
    return std::nullopt;
  }
  // The next binary message, skipping text.
  static std::optional<Data> next_binary(TestClient& client) {
    for (;;) {
      const auto frame = client.receive_frame();
      if (!frame) return std::nullopt;
      if (frame->binary) return parse_binary(frame->data);
    }
  }
  void publish(std::uint64_t time_ns, const std::string& topic, const Json& payload) {
    server_->publish_foxglove(
        time_ns, {{topic, "test" + topic, std::make_shared<const std::string>(R"({"type":"object"})"),
                   payload.dump()}});
  }
  // Waits until the server has handled everything the client sent before (getParameters is
  // answered in order).
  static void sync(TestClient& client) {
    ASSERT_TRUE(client.send(Json{{"op", "getParameters"}, {"parameterNames", Json::array()},
                                 {"id", "sync"}}));
    for (;;) {
      const auto reply = next_op(client, "parameterValues");
      ASSERT_TRUE(reply.has_value());
      if (reply->value("id", "") == "sync") return;
    }
  }

  std::unique_ptr<LinkServer> server_;
};

TEST_F(FoxgloveServerTest, NegotiatesTheSubprotocolAndSendsServerInfo) {
  start();
  auto client = open();
  ASSERT_TRUE(client->open()) << client->handshake_response().result_int();
  EXPECT_EQ(client->handshake_response()[testing::http::field::sec_websocket_protocol],
            kSubprotocol);
  const auto info = client->receive();
  ASSERT_TRUE(info.has_value());
  EXPECT_EQ((*info)["op"], "serverInfo");
  EXPECT_EQ((*info)["capabilities"], Json({"time", "parameters", "parametersSubscribe"}));
  EXPECT_EQ(server_->stats().foxglove_clients, 1U);
  EXPECT_TRUE(server_->foxglove_interest().connected);
  EXPECT_EQ(server_->foxglove_url(),
            "ws://127.0.0.1:" + std::to_string(server_->port()) + "/foxglove?token=" + kToken);
}

TEST_F(FoxgloveServerTest, RefusesAMissingSubprotocolAWrongTokenAndAForeignOrigin) {
  start();
  auto no_protocol = open(std::string("?token=") + kToken, {});
  EXPECT_FALSE(no_protocol->open());
  EXPECT_EQ(no_protocol->handshake_response().result_int(), 400);
  auto wrong = open("?token=not-the-token-0123456789");
  EXPECT_FALSE(wrong->open());
  EXPECT_EQ(wrong->handshake_response().result_int(), 401);
  auto none = open("");
  EXPECT_FALSE(none->open());
  EXPECT_EQ(none->handshake_response().result_int(), 401);
  auto foreign = open(std::string("?token=") + kToken,
                      {{"Sec-WebSocket-Protocol", kSubprotocol}, {"Origin", "https://evil.example"}});
  EXPECT_FALSE(foreign->open());
  EXPECT_EQ(foreign->handshake_response().result_int(), 403);
  // The console's own WebSocket takes no token in the query (its page trades it for a cookie).
  TestClient console(server_->port(), std::string("/ws?token=") + kToken);
  EXPECT_FALSE(console.open());
  EXPECT_EQ(server_->stats().foxglove_connections, 0U);
}

TEST_F(FoxgloveServerTest, AdvertisesChannelsAndSendsOnlyWhatIsSubscribed) {
  start();
  auto client = open();
  ASSERT_TRUE(client->open());
  ASSERT_TRUE(next_op(*client, "serverInfo").has_value());
  publish(1'000'000'000, "/status", {{"mission_time_s", 1.0}});
  const auto advertise = next_op(*client, "advertise");
  ASSERT_TRUE(advertise.has_value());
  ASSERT_EQ((*advertise)["channels"].size(), 1U);
  const Json channel = (*advertise)["channels"][0];
  EXPECT_EQ(channel["topic"], "/status");
  EXPECT_EQ(channel["schemaName"], "test/status");
  EXPECT_EQ(channel["schema"], R"({"type":"object"})");
  // Not subscribed: only the time.
  const auto first = next_binary(*client);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->opcode, foxglove::kTimeOpcode);
  EXPECT_EQ(first->time_ns, 1'000'000'000U);

  ASSERT_TRUE(client->send(Json{{"op", "subscribe"},
                                {"subscriptions", {{{"id", 7}, {"channelId", channel["id"]}}}}}));
  sync(*client);
  EXPECT_EQ(server_->foxglove_interest().subscribed, std::vector<std::string>{"/status"});
  publish(1'500'000'000, "/status", {{"mission_time_s", 1.5}});
  const auto time = next_binary(*client);
  ASSERT_TRUE(time.has_value());
  EXPECT_EQ(time->opcode, foxglove::kTimeOpcode);
  const auto data = next_binary(*client);
  ASSERT_TRUE(data.has_value());
  EXPECT_EQ(data->opcode, foxglove::kMessageDataOpcode);
  EXPECT_EQ(data->subscription, 7U);
  EXPECT_EQ(data->time_ns, 1'500'000'000U);
  EXPECT_EQ(Json::parse(data->payload)["mission_time_s"], 1.5);

  // A second channel appears: advertised to the connected client; a new client hears both.
  publish(2'000'000'000, "/imu", {{"yaw_rate_radps", 0.25}});
  const auto more = next_op(*client, "advertise");
  ASSERT_TRUE(more.has_value());
  EXPECT_EQ((*more)["channels"][0]["topic"], "/imu");
  auto late = open();
  ASSERT_TRUE(late->open());
  ASSERT_TRUE(next_op(*late, "serverInfo").has_value());
  const auto both = next_op(*late, "advertise");
  ASSERT_TRUE(both.has_value());
  EXPECT_EQ((*both)["channels"].size(), 2U);

  // Unsubscribed: the time still comes, the data no more.
  ASSERT_TRUE(client->send(Json{{"op", "unsubscribe"}, {"subscriptionIds", {7}}}));
  sync(*client);
  EXPECT_TRUE(server_->foxglove_interest().subscribed.empty());
  publish(3'000'000'000, "/status", {{"mission_time_s", 3.0}});
  publish(4'000'000'000, "/status", {{"mission_time_s", 4.0}});
  for (const std::uint64_t expected : {3'000'000'000ULL, 4'000'000'000ULL}) {
    const auto next = next_binary(*client);
    ASSERT_TRUE(next.has_value());
    EXPECT_EQ(next->opcode, foxglove::kTimeOpcode);
    EXPECT_EQ(next->time_ns, expected);
  }
}

TEST_F(FoxgloveServerTest, ClientErrorsAreStatusMessagesAndNobodyIsDisconnected) {
  start();
  TestClient console(server_->port(), "/ws", {{"Authorization", std::string("Bearer ") + kToken}});
  ASSERT_TRUE(console.open());
  ASSERT_TRUE(console.receive_type("hello").has_value());
  auto client = open();
  ASSERT_TRUE(client->open());
  ASSERT_TRUE(next_op(*client, "serverInfo").has_value());
  const auto error_after = [&](const std::string& text, bool binary = false) {
    EXPECT_TRUE(client->send(text, binary));
    const auto status = next_op(*client, "status");
    EXPECT_TRUE(status.has_value()) << text;
    if (!status) return std::string();
    EXPECT_EQ((*status)["level"], 2) << text;
    return (*status)["message"].get<std::string>();
  };
  EXPECT_NE(error_after("{not json").find("malformed JSON"), std::string::npos);
  EXPECT_NE(error_after(R"({"op":"clientAdvertise","channels":[]})").find("not supported"),
            std::string::npos);
  EXPECT_EQ(error_after(R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":99}]})"),
            "subscribe: channel 99 is not advertised");
  EXPECT_NE(error_after("\x01\x02", true).find("binary"), std::string::npos);
  // Still connected, and so is the console.
  publish(5'000'000'000, "/status", {{"mission_time_s", 5.0}});
  const auto advertise = next_op(*client, "advertise");
  ASSERT_TRUE(advertise.has_value());
  server_->publish_status({{"mission_time_s", 5.0}});
  EXPECT_TRUE(console.receive_type("status").has_value());
  const ServerStats stats = server_->stats();
  EXPECT_EQ(stats.foxglove_clients, 1U);
  EXPECT_EQ(stats.clients, 1U);
  EXPECT_EQ(stats.handler_failures, 0U);
}

TEST_F(FoxgloveServerTest, ParametersAreTheSettingsInForceAndOnlyTheControllerSetsThem) {
  start();
  auto client = open();
  ASSERT_TRUE(client->open());
  ASSERT_TRUE(next_op(*client, "serverInfo").has_value());
  const Json settings = Json::parse(R"({"max_drop_v":1.5,"load_distribution":"off",
      "behaviours":{"power_management":true,"slant_response":true,"contract_on_turn":true,
      "axle_placement":false},"speed_scale":1.0})");
  ASSERT_TRUE(client->send(Json{{"op", "subscribeParameterUpdates"},
                                {"parameterNames", {"speed_scale", "max_drop_v"}}}));
  sync(*client);
  server_->publish_status({{"mission_time_s", 0.0}, {"settings", settings}});
  // The first settings are updates too (from nothing).
  auto update = next_op(*client, "parameterValues");
  ASSERT_TRUE(update.has_value());
  EXPECT_EQ((*update)["parameters"].size(), 2U);

  ASSERT_TRUE(client->send(Json{{"op", "getParameters"},
                                {"parameterNames", {"behaviours.axle_placement", "nonsense"}},
                                {"id", "q"}}));
  const auto values = next_op(*client, "parameterValues");
  ASSERT_TRUE(values.has_value());
  EXPECT_EQ((*values)["id"], "q");
  EXPECT_EQ((*values)["parameters"],
            Json::parse(R"([{"name":"behaviours.axle_placement","value":false}])"));
  const auto unknown = next_op(*client, "status");
  ASSERT_TRUE(unknown.has_value());
  EXPECT_EQ((*unknown)["message"], "getParameters: no parameter nonsense");

  // Setting: refused, the control rules' own words, nothing reaches the driver.
  ASSERT_TRUE(client->send(Json{{"op", "setParameters"},
                                {"parameters", {{{"name", "speed_scale"}, {"value", 0.5}}}}}));
  const auto refused = next_op(*client, "status");
  ASSERT_TRUE(refused.has_value());
  EXPECT_EQ((*refused)["level"], 2);
  EXPECT_NE((*refused)["message"].get<std::string>().find(kReadOnlyMessage), std::string::npos);
  ASSERT_TRUE(client->send(Json{{"op", "setParameters"},
                                {"parameters", {{{"name", "speed_scale"}, {"value", 7}}}}}));
  const auto range = next_op(*client, "status");
  ASSERT_TRUE(range.has_value());
  EXPECT_EQ((*range)["message"],
            "setParameters: speed_scale: 7 is out of range; allowed [0, 1]");
  EXPECT_TRUE(server_->take_inbound().empty());

  // The console's configure changes the settings in force: the update names only what changed.
  Json changed = settings;
  changed["speed_scale"] = 0.25;
  changed["behaviours"]["slant_response"] = false;  // not subscribed to
  server_->publish_status({{"mission_time_s", 1.0}, {"settings", changed}});
  update = next_op(*client, "parameterValues");
  ASSERT_TRUE(update.has_value());
  EXPECT_EQ((*update)["parameters"],
            Json::parse(R"([{"name":"speed_scale","value":0.25,"type":"float64"}])"));
}

TEST_F(FoxgloveServerTest, ASlowClientLosesOldDataNotItsConnection) {
  ServerOptions options;
  options.foxglove_queue_messages = 8;
  start(options);
  auto client = open();
  ASSERT_TRUE(client->open());
  ASSERT_TRUE(next_op(*client, "serverInfo").has_value());
  const std::string big(256 * 1024, 'x');
  publish(1, "/big", {{"x", big}});
  const auto advertise = next_op(*client, "advertise");
  ASSERT_TRUE(advertise.has_value());
  ASSERT_TRUE(client->send(Json{{"op", "subscribe"},
                                {"subscriptions", {{{"id", 1}, {"channelId", (*advertise)["channels"][0]["id"]}}}}}));
  sync(*client);
  // 64 MB it does not read, far beyond the socket buffers and the queue of 8.
  for (std::uint64_t k = 2; k < 258; ++k) publish(k, "/big", {{"x", big}});
  const auto deadline = std::chrono::steady_clock::now() + testing::kWait;
  while (server_->stats().foxglove_messages_dropped == 0 &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(1ms);
  }
  EXPECT_GT(server_->stats().foxglove_messages_dropped, 0U);
  EXPECT_EQ(server_->stats().dropped_slow, 0U);
  // It reads again: the newest data is there, and it can still ask.
  std::uint64_t newest = 0;
  while (newest < 257) {
    const auto next = next_binary(*client);
    ASSERT_TRUE(next.has_value()) << "after " << newest;
    newest = next->time_ns;
  }
  sync(*client);
  EXPECT_EQ(server_->stats().foxglove_clients, 1U);
}

}  // namespace
}  // namespace marsokhod::link
