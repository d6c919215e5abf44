// The server on loopback with real WebSocket clients: the token, the control rules as the
// consoles see them, the controller's disconnect as a stop, status to every client (coalesced),
// errors that name the field, the bounded queues, stale input, rate limits and failed handlers.
// Every wait has a deadline (test_client.hpp).
#include "link/link_server.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>

#include "core/navigation/mission.hpp"
#include "test_client.hpp"

namespace marsokhod::link {
namespace {

using namespace std::chrono_literals;
using testing::TestClient;

constexpr const char* kToken = "test-token-0123456789";

class LinkServerTest : public ::testing::Test {
 protected:
  void start(ServerOptions options = {}) {
    options.listen = {"127.0.0.1", 0};
    options.token = kToken;
    server_ = std::make_unique<LinkServer>(params_, std::move(options));
    server_->start();
  }
  std::unique_ptr<TestClient> connect(const std::string& token = kToken) {
    return std::make_unique<TestClient>(server_->port(), "/ws",
                                        testing::Headers{{"Authorization", "Bearer " + token}});
  }
  // A connected client and its hello.
  std::pair<std::unique_ptr<TestClient>, nlohmann::json> console() {
    auto client = connect();
    EXPECT_TRUE(client->open()) << client->error().message();
    auto hello = client->receive_type("hello");
    EXPECT_TRUE(hello.has_value());
    return {std::move(client), hello.value_or(nlohmann::json{})};
  }
  // Polls take_inbound (short bounded sleeps) until `count` commands arrived or the deadline.
  std::vector<InboundCommand> wait_inbound(std::size_t count) {
    std::vector<InboundCommand> all;
    const auto deadline = std::chrono::steady_clock::now() + testing::kWait;
    while (all.size() < count && std::chrono::steady_clock::now() < deadline) {
      for (auto& command : server_->take_inbound()) all.push_back(std::move(command));
      if (all.size() < count) std::this_thread::sleep_for(1ms);
    }
    return all;
  }
  // The client takes control; its inbound take_control and stop are consumed.
  void take_control(TestClient& client) {
    ASSERT_TRUE(client.send(nlohmann::json{{"type", "take_control"}}));
    const auto control = client.receive_type("control");
    ASSERT_TRUE(control.has_value());
    ASSERT_EQ((*control)["read_only"], false);
    ASSERT_EQ(wait_inbound(2).size(), 2U);
  }

  Params params_;
  std::unique_ptr<LinkServer> server_;
};

double now_ms() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// A reading as the console sends it: seq counting up (one counter for all clients is still
// increasing for each), sent now.
nlohmann::json gamepad(double left_stick_y) {
  static std::atomic<std::uint64_t> seq{0};
  return {{"type", "gamepad"},
          {"seq", ++seq},
          {"sent_ms", now_ms()},
          {"axes", {0.0, left_stick_y, 0.0, 0.0}},
          {"buttons", std::vector<bool>(17, false)}};
}

nlohmann::json stamped(double left_stick_y, std::uint64_t seq, double sent_ms) {
  nlohmann::json message = gamepad(left_stick_y);
  message["seq"] = seq;
  message["sent_ms"] = sent_ms;
  return message;
}

TEST_F(LinkServerTest, GreetsAClientWithTheRightToken) {
  start();
  auto [client, hello] = console();
  EXPECT_EQ(hello["type"], "hello");
  EXPECT_EQ(hello["protocol"], 2);
  EXPECT_GE(hello["client_id"].get<int>(), 1);
  EXPECT_TRUE(hello["controller"].is_null());
  EXPECT_EQ(hello["read_only"], true);
  EXPECT_NEAR(hello["velocity_limits"]["v_mps"].get<double>(),
              navigation::max_velocity_mps(params_), 1e-12);
  EXPECT_NEAR(hello["velocity_limits"]["yaw_radps"].get<double>(),
              navigation::max_yaw_rate_radps(params_), 1e-12);
  EXPECT_EQ(server_->stats().clients, 1U);
  EXPECT_NE(server_->console_url().find("/?token=" + std::string(kToken)), std::string::npos);
}

TEST_F(LinkServerTest, RefusesAWrongOrMissingTokenWith401ThenBacksOff) {
  ServerOptions options;
  options.auth_backoff_first_s = 60.0;  // the second try certainly falls within it
  start(options);
  TestClient wrong(server_->port(), "/ws",
                   testing::Headers{{"Authorization", "Bearer wrong-token-0123456789"}});
  EXPECT_FALSE(wrong.open());
  EXPECT_EQ(wrong.error(), testing::websocket::error::upgrade_declined);
  EXPECT_EQ(wrong.handshake_response().result_int(), 401);
  // The same address again, even with the right token: refused unseen until the back-off ends.
  for (const std::string token : {"", kToken}) {
    TestClient next(server_->port(), "/ws", testing::Headers{{"Authorization", "Bearer " + token}});
    EXPECT_FALSE(next.open()) << token;
    EXPECT_EQ(next.handshake_response().result_int(), 429) << token;
  }
  EXPECT_EQ(server_->stats().unauthorized, 1U);
  EXPECT_EQ(server_->stats().auth_throttled, 2U);
  EXPECT_EQ(server_->stats().clients, 0U);
  const auto response = testing::http_request(server_->port(), testing::http::verb::get, "/ws");
  EXPECT_EQ(response.result_int(), 404);  // not an upgrade, and no file of that name
}

TEST_F(LinkServerTest, TheTokenInTheQueryNoLongerOpensAWebSocket) {
  start();
  TestClient client(server_->port(), std::string("/ws?token=") + kToken);
  EXPECT_FALSE(client.open());
  EXPECT_EQ(client.handshake_response().result_int(), 401);
}

TEST_F(LinkServerTest, ASecondClientIsReadOnlyUntilItTakesControl) {
  start();
  auto [first, first_hello] = console();
  take_control(*first);
  auto [second, second_hello] = console();
  EXPECT_EQ(second_hello["controller"], first_hello["client_id"]);
  EXPECT_EQ(second_hello["read_only"], true);

  ASSERT_TRUE(second->send(gamepad(-1.0)));
  const auto refused = second->receive_type("error");
  ASSERT_TRUE(refused.has_value());
  EXPECT_EQ((*refused)["field"], "type");
  EXPECT_EQ((*refused)["message"], "read-only: take control first");
  EXPECT_TRUE(server_->take_inbound().empty());

  ASSERT_TRUE(second->send(nlohmann::json{{"type", "take_control"}}));
  const auto lost = first->receive_type("control");
  ASSERT_TRUE(lost.has_value());
  EXPECT_EQ((*lost)["lost_control"], true);
  EXPECT_EQ((*lost)["read_only"], true);
  EXPECT_EQ((*lost)["controller"], second_hello["client_id"]);
  const auto gained = second->receive_type("control");
  ASSERT_TRUE(gained.has_value());
  EXPECT_EQ((*gained)["read_only"], false);
  EXPECT_EQ(wait_inbound(2).size(), 2U);  // take_control, stop

  ASSERT_TRUE(second->send(gamepad(-0.5)));
  ASSERT_TRUE(first->send(gamepad(1.0)));
  ASSERT_TRUE(first->receive_type("error").has_value());
  const auto inbound = wait_inbound(1);
  ASSERT_EQ(inbound.size(), 1U);
  EXPECT_EQ(inbound[0].client_id, second_hello["client_id"].get<ClientId>());
  EXPECT_EQ(std::get<GamepadMessage>(inbound[0].message).reading.axes[1], -0.5);
}

TEST_F(LinkServerTest, AnyClientMayStopAndAStopFromAnotherTakesControlAway) {
  start();
  auto [controller, controller_hello] = console();
  take_control(*controller);
  auto [watcher, watcher_hello] = console();
  const auto watcher_id = watcher_hello["client_id"].get<ClientId>();
  const auto controller_id = controller_hello["client_id"].get<ClientId>();
  ASSERT_TRUE(watcher->send(nlohmann::json{{"type", "stop"}}));
  const auto inbound = wait_inbound(1);
  ASSERT_EQ(inbound.size(), 1U);
  EXPECT_TRUE(std::holds_alternative<StopMessage>(inbound[0].message));
  EXPECT_EQ(inbound[0].client_id, watcher_id);
  const std::string reason = "client " + std::to_string(watcher_id) + " pressed STOP; client " +
                             std::to_string(controller_id) + " lost control";
  EXPECT_EQ(inbound[0].reason, reason);
  EXPECT_FALSE(server_->stats().controller.has_value());
  const auto lost = controller->receive_type("control");
  ASSERT_TRUE(lost.has_value());
  EXPECT_EQ((*lost)["lost_control"], true);
  EXPECT_EQ((*lost)["reason"], reason);
  // Every console is told who stopped and why.
  for (TestClient* client : {controller.get(), watcher.get()}) {
    const auto stopped = client->receive_type("stopped");
    ASSERT_TRUE(stopped.has_value());
    EXPECT_EQ((*stopped)["by"], watcher_id);
    EXPECT_EQ((*stopped)["reason"], reason);
  }
  // The former controller's readings are refused now.
  ASSERT_TRUE(controller->send(gamepad(-1.0)));
  EXPECT_EQ(controller->receive_type("error").value_or(nlohmann::json{})["message"],
            "read-only: take control first");
}

TEST_F(LinkServerTest, TheControllersOwnStopKeepsControl) {
  start();
  auto [controller, hello] = console();
  take_control(*controller);
  ASSERT_TRUE(controller->send(nlohmann::json{{"type", "stop"}}));
  const auto inbound = wait_inbound(1);
  ASSERT_EQ(inbound.size(), 1U);
  EXPECT_EQ(inbound[0].reason, "client " + hello["client_id"].dump() + " pressed STOP");
  EXPECT_TRUE(controller->receive_type("stopped").has_value());
  EXPECT_EQ(server_->stats().controller, hello["client_id"].get<ClientId>());
}

TEST_F(LinkServerTest, StaleAndOutOfOrderReadingsAreDropped) {
  start();
  auto [client, hello] = console();
  take_control(*client);
  const double t = now_ms();
  ASSERT_TRUE(client->send(stamped(-0.1, 10, t)));
  ASSERT_TRUE(client->send(stamped(-0.2, 11, t - 5000.0)));  // held up 5 s in a stall
  ASSERT_TRUE(client->send(stamped(-0.3, 11, now_ms())));    // seq repeated
  ASSERT_TRUE(client->send(stamped(-0.4, 9, now_ms())));     // seq going back
  ASSERT_TRUE(client->send(stamped(-0.5, 12, now_ms())));
  ASSERT_TRUE(client->send(nlohmann::json{{"type", "ping"}}));
  ASSERT_TRUE(client->receive_type("pong").has_value());  // all five handled
  const auto inbound = server_->take_inbound();
  ASSERT_EQ(inbound.size(), 2U);
  EXPECT_EQ(std::get<GamepadMessage>(inbound[0].message).reading.axes[1], -0.1);
  EXPECT_EQ(std::get<GamepadMessage>(inbound[1].message).reading.axes[1], -0.5);
  EXPECT_EQ(server_->stats().stale_dropped, 3U);
}

TEST_F(LinkServerTest, MessagesBeyondTheRateAreDroppedAndCounted) {
  ServerOptions options;
  options.message_rate_per_s = 1e-6;  // no refill within the test: exactly the burst passes
  options.message_burst = 5.0;
  start(options);
  auto [client, hello] = console();
  for (int i = 0; i < 20; ++i) ASSERT_TRUE(client->send(nlohmann::json{{"type", "ping"}}));
  int pongs = 0;
  while (client->receive_type("pong", 300ms).has_value()) ++pongs;
  EXPECT_EQ(pongs, 5);
  EXPECT_EQ(server_->stats().rate_limited, 15U);
}

TEST_F(LinkServerTest, ATakeControlFloodIsNotReBroadcast) {
  start();
  auto [holder, holder_hello] = console();
  auto [watcher, watcher_hello] = console();
  for (int i = 0; i < 20; ++i) {
    ASSERT_TRUE(holder->send(nlohmann::json{{"type", "take_control"}}));
  }
  ASSERT_TRUE(holder->send(nlohmann::json{{"type", "ping"}}));
  ASSERT_TRUE(holder->receive_type("pong").has_value());
  ASSERT_TRUE(watcher->send(nlohmann::json{{"type", "ping"}}));
  int controls = 0;
  for (;;) {
    const auto message = watcher->receive();
    ASSERT_TRUE(message.has_value());
    if ((*message)["type"] == "pong") break;
    if ((*message)["type"] == "control") ++controls;
  }
  EXPECT_EQ(controls, 1);  // the first take; the repeats went to the holder alone
  EXPECT_EQ(server_->stats().rate_limited, 20U - 8U);  // control_burst 8
}

TEST_F(LinkServerTest, AFailingHandlerClosesItsSessionAndStopsTheRover) {
  ServerOptions options;
  options.message_observer = [](ClientId, std::string_view text) {
    if (text == "boom") throw std::runtime_error("injected failure");
  };
  start(options);
  auto [controller, hello] = console();
  take_control(*controller);
  auto [watcher, watcher_hello] = console();
  ASSERT_TRUE(controller->send(std::string("boom")));
  EXPECT_TRUE(controller->wait_closed());
  const auto inbound = wait_inbound(1);
  ASSERT_EQ(inbound.size(), 1U);
  EXPECT_TRUE(std::holds_alternative<StopMessage>(inbound[0].message));
  EXPECT_NE(inbound[0].reason.find("disconnected"), std::string::npos) << inbound[0].reason;
  const auto control = watcher->receive_type("control");
  ASSERT_TRUE(control.has_value());
  EXPECT_TRUE((*control)["controller"].is_null());
  EXPECT_EQ(server_->stats().handler_failures, 1U);
  auto [next, next_hello] = console();  // and it serves on
  EXPECT_EQ(next_hello["type"], "hello");
}

TEST_F(LinkServerTest, TheControllersDisconnectBecomesAStop) {
  start();
  auto [controller, hello] = console();
  take_control(*controller);
  auto [watcher, watcher_hello] = console();
  controller->drop();
  const auto inbound = wait_inbound(1);
  ASSERT_EQ(inbound.size(), 1U);
  EXPECT_TRUE(std::holds_alternative<StopMessage>(inbound[0].message));
  EXPECT_EQ(inbound[0].client_id, hello["client_id"].get<ClientId>());
  EXPECT_NE(inbound[0].reason.find("disconnected"), std::string::npos) << inbound[0].reason;
  const auto control = watcher->receive_type("control");
  ASSERT_TRUE(control.has_value());
  EXPECT_TRUE((*control)["controller"].is_null());
  EXPECT_EQ(server_->stats().controller_disconnects, 1U);
  EXPECT_FALSE(server_->stats().controller.has_value());
}

TEST_F(LinkServerTest, AWatchersDisconnectChangesNothing) {
  start();
  auto [controller, hello] = console();
  take_control(*controller);
  {
    auto [watcher, watcher_hello] = console();
    watcher->drop();
  }
  ASSERT_TRUE(controller->send(nlohmann::json{{"type", "ping"}}));
  ASSERT_TRUE(controller->receive_type("pong").has_value());
  EXPECT_TRUE(server_->take_inbound().empty());
  EXPECT_EQ(server_->stats().controller, hello["client_id"].get<ClientId>());
}

TEST_F(LinkServerTest, APublishedStatusReachesEveryClient) {
  start();
  auto [first, first_hello] = console();
  auto [second, second_hello] = console();
  server_->publish_status({{"cycle", 42}, {"supply_v", 24.0}});
  for (TestClient* client : {first.get(), second.get()}) {
    const auto status = client->receive_type("status");
    ASSERT_TRUE(status.has_value());
    EXPECT_EQ((*status)["status"]["cycle"], 42);
    EXPECT_EQ((*status)["status"]["supply_v"], 24.0);
  }
}

TEST_F(LinkServerTest, SendsOnlyTheNewestStatusPerPeriod) {
  ServerOptions options;
  options.status_period_s = 1.0;  // long enough that 2 and 3 land in one period
  start(options);
  auto [client, hello] = console();
  server_->publish_status({{"cycle", 1}});
  ASSERT_EQ(client->receive_type("status").value_or(nlohmann::json{})["status"]["cycle"], 1);
  server_->publish_status({{"cycle", 2}});
  server_->publish_status({{"cycle", 3}});
  const auto next = client->receive_type("status", 3s);
  ASSERT_TRUE(next.has_value());
  EXPECT_EQ((*next)["status"]["cycle"], 3);
  EXPECT_FALSE(client->receive_type("status", 50ms).has_value());
  EXPECT_EQ(server_->stats().statuses_published, 3U);
  EXPECT_EQ(server_->stats().statuses_sent, 2U);
}

TEST_F(LinkServerTest, ANewerStatusKeepsTheSoilPatchOfTheOneItReplaces) {
  // The simulator sends the soil's patch with one status a second; if a newer status replaces
  // that one before it is sent, the patch goes with the newer one (its own patch wins).
  ServerOptions options;
  options.status_period_s = 1.0;
  start(options);
  auto [client, hello] = console();
  server_->publish_status({{"cycle", 1}});
  ASSERT_TRUE(client->receive_type("status").has_value());
  server_->publish_status({{"cycle", 2}, {"truth", {{"soil", {{"rows", 2}}}}}});
  server_->publish_status({{"cycle", 3}, {"truth", {{"supply_v", 24.0}}}});
  const auto next = client->receive_type("status", 3s);
  ASSERT_TRUE(next.has_value());
  EXPECT_EQ((*next)["status"]["cycle"], 3);
  EXPECT_EQ((*next)["status"]["truth"]["supply_v"], 24.0);
  EXPECT_EQ((*next)["status"]["truth"]["soil"]["rows"], 2);
  server_->publish_status({{"cycle", 4}, {"truth", {{"soil", {{"rows", 5}}}}}});
  server_->publish_status({{"cycle", 5}, {"truth", {{"soil", {{"rows", 7}}}}}});
  const auto last = client->receive_type("status", 3s);
  ASSERT_TRUE(last.has_value());
  EXPECT_EQ((*last)["status"]["truth"]["soil"]["rows"], 7);
}

TEST_F(LinkServerTest, AMalformedMessageNamesTheFieldAndSendsNothingOn) {
  start();
  auto [client, hello] = console();
  take_control(*client);
  auto bad = gamepad(0.0);
  bad["axes"][1] = 1.7;
  ASSERT_TRUE(client->send(bad));
  const auto error = client->receive_type("error");
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ((*error)["field"], "axes[1]");
  EXPECT_EQ((*error)["message"], "axes[1]: 1.7 is out of range; allowed \u22121..1");
  ASSERT_TRUE(client->send(std::string(R"({"type":"gamepad",)")));
  EXPECT_EQ(client->receive_type("error").value_or(nlohmann::json{})["field"], "json");
  ASSERT_TRUE(client->send(std::string(R"({"type":"stop"})"), true));
  EXPECT_EQ(client->receive_type("error").value_or(nlohmann::json{})["field"], "json");
  EXPECT_TRUE(server_->take_inbound().empty());
  EXPECT_EQ(server_->stats().messages_rejected, 3U);
}

TEST_F(LinkServerTest, AnswersPing) {
  start();
  auto [client, hello] = console();
  ASSERT_TRUE(client->send(nlohmann::json{{"type", "ping"}}));
  EXPECT_TRUE(client->receive_type("pong").has_value());
  EXPECT_TRUE(server_->take_inbound().empty());
}

TEST_F(LinkServerTest, RefusesCommandsWhenTheInboundQueueIsFullButNeverAStop) {
  ServerOptions options;
  options.inbound_queue_commands = 3;
  start(options);
  auto [controller, hello] = console();
  take_control(*controller);
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(controller->send(gamepad(0.0)));
  ASSERT_TRUE(controller->send(gamepad(0.0)));
  const auto refused = controller->receive_type("error");
  ASSERT_TRUE(refused.has_value());
  EXPECT_NE((*refused)["message"].get<std::string>().find("queue full"), std::string::npos);
  ASSERT_TRUE(controller->send(nlohmann::json{{"type", "stop"}}));
  ASSERT_TRUE(controller->send(nlohmann::json{{"type", "ping"}}));
  ASSERT_TRUE(controller->receive_type("pong").has_value());  // the stop was handled before
  const auto inbound = server_->take_inbound();
  ASSERT_EQ(inbound.size(), 3U);
  EXPECT_TRUE(std::holds_alternative<StopMessage>(inbound.back().message));
  EXPECT_EQ(server_->stats().inbound_refused, 2U);
}

TEST_F(LinkServerTest, RefusesClientsBeyondTheLimitWith503) {
  ServerOptions options;
  options.max_clients = 1;
  start(options);
  auto [first, hello] = console();
  TestClient second(server_->port(), "/ws",
                    testing::Headers{{"Authorization", std::string("Bearer ") + kToken}});
  EXPECT_FALSE(second.open());
  EXPECT_EQ(second.handshake_response().result_int(), 503);
}

TEST_F(LinkServerTest, DropsAClientThatDoesNotReadWithoutStallingOthers) {
  ServerOptions options;
  options.status_period_s = 0.0;
  options.client_queue_messages = 2;
  start(options);
  auto [stalled, stalled_hello] = console();
  auto [reader, reader_hello] = console();
  // Statuses large enough to fill the loopback socket buffers within a few dozen sends.
  const std::string filler(1 << 20, 'x');
  for (int i = 0; i < 200 && server_->stats().dropped_slow == 0; ++i) {
    server_->publish_status({{"cycle", i}, {"filler", filler}});
    const auto status = reader->receive_type("status");
    ASSERT_TRUE(status.has_value()) << "the reading client stalled at status " << i;
  }
  EXPECT_EQ(server_->stats().dropped_slow, 1U);
  EXPECT_TRUE(stalled->wait_closed());
  server_->publish_status({{"cycle", -1}});
  EXPECT_EQ(reader->receive_type("status").value_or(nlohmann::json{})["status"]["cycle"], -1);
}

TEST_F(LinkServerTest, StopClosesEveryConnectionAndJoins) {
  start();
  auto [client, hello] = console();
  server_->stop();
  EXPECT_TRUE(client->wait_closed());
  server_->stop();  // idempotent
  EXPECT_THROW(server_->start(), std::logic_error);
}

TEST_F(LinkServerTest, ReportsAPortInUse) {
  start();
  ServerOptions options;
  options.listen = {"127.0.0.1", server_->port()};
  LinkServer second(params_, options);
  try {
    second.start();
    FAIL() << "listened twice on one port";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("--listen"), std::string::npos) << error.what();
  }
}

TEST(LinkServerOptions, RejectsBadOptions) {
  const Params params;
  ServerOptions short_token;
  short_token.token = "abc";
  EXPECT_THROW(LinkServer(params, short_token), std::invalid_argument);
  ServerOptions period;
  period.status_period_s = -0.1;
  EXPECT_THROW(LinkServer(params, period), std::invalid_argument);
  ServerOptions zero;
  zero.client_queue_messages = 0;
  EXPECT_THROW(LinkServer(params, zero), std::invalid_argument);
  ServerOptions address;
  address.listen.address = "rover";
  EXPECT_THROW(LinkServer(params, address), std::invalid_argument);
  EXPECT_EQ(LinkServer(params, {}).token().size(), 32U);
}

}  // namespace
}  // namespace marsokhod::link
