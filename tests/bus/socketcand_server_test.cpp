#include "bus/socketcand_server.hpp"

#include <gtest/gtest.h>

#include <condition_variable>
#include <mutex>

#include "bus/socketcand_client.hpp"
#include "core/protocol/codec.hpp"
#include "tcp_test_peer.hpp"

namespace marsokhod::bus {
namespace {

using std::chrono::milliseconds;
using testing::kPatience;
using testing::TcpConnection;

// The frames a client sent, as the simulator would consume them; waits are bounded.
class FrameSink {
 public:
  void push(const protocol::CanFrame& frame) {
    const std::lock_guard lock(mutex_);
    frames_.push_back(frame);
    arrived_.notify_all();
  }
  std::vector<protocol::CanFrame> wait_for(std::size_t count) {
    std::unique_lock lock(mutex_);
    arrived_.wait_for(lock, kPatience, [&] { return frames_.size() >= count; });
    return frames_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::vector<protocol::CanFrame> frames_;
};

SocketcandServer::Config test_config() {
  SocketcandServer::Config config;
  config.port = 0;  // ephemeral: tests never collide with a running sim
  config.rawmode_grace = milliseconds(0);
  return config;
}

SocketcandClient::Config client_config(const SocketcandServer& server) {
  SocketcandClient::Config config;
  config.port = server.port();
  return config;
}

TcpConnection raw_client(const SocketcandServer& server) {
  auto peer = TcpConnection::connect_loopback(server.port());
  EXPECT_EQ(peer.read_message(), "< hi >");
  return peer;
}

TcpConnection raw_client_in_rawmode(const SocketcandServer& server) {
  auto peer = raw_client(server);
  peer.send_text("< open can0 >");
  EXPECT_EQ(peer.read_message(), "< ok >");
  peer.send_text("< rawmode >");
  EXPECT_EQ(peer.read_message(), "< ok >");
  return peer;
}

std::vector<protocol::CanFrame> receive_frames(CanTransport& transport, std::size_t count) {
  std::vector<protocol::CanFrame> frames;
  for (int i = 0; i < 50 && frames.size() < count; ++i) {
    for (const auto& f : transport.receive(milliseconds(100))) frames.push_back(f);
  }
  return frames;
}

TEST(SocketcandServer, RoundTripWithOurClient) {
  // µ3 control request in, µ3 control response out, built and checked by the protocol codec.
  const protocol::ControlRequest request{3, true, true, 300};
  const protocol::ControlResponse response{3, 0x1234, 0x0102, 0x0A0B, true, 0x1FF};
  SocketcandServer* server_pointer = nullptr;
  FrameSink sink;
  SocketcandServer server(test_config(), [&](const protocol::CanFrame& frame) {
    sink.push(frame);
    const auto decoded = protocol::decode(frame);
    if (decoded && decoded.message() == protocol::Message{request}) {
      server_pointer->broadcast(protocol::encode(response), 12.5);
    }
  });
  server_pointer = &server;
  server.start();
  SocketcandClient client(client_config(server));
  client.send(protocol::encode(request));
  const auto frames = receive_frames(client, 1);
  ASSERT_EQ(frames.size(), 1u);
  const auto decoded = protocol::decode(frames[0]);
  ASSERT_TRUE(decoded) << decoded.error().reason;
  EXPECT_EQ(decoded.message(), protocol::Message{response});
  EXPECT_EQ(sink.wait_for(1), std::vector<protocol::CanFrame>{protocol::encode(request)});
  const ServerCounters counters = server.counters();
  EXPECT_EQ(counters.clients_accepted, 1u);
  EXPECT_EQ(counters.frames_from_clients, 1u);
  EXPECT_EQ(counters.frames_broadcast, 1u);
  EXPECT_EQ(counters.malformed_messages, 0u);
}

TEST(SocketcandServer, SpeaksTheSocketcandHandshake) {
  SocketcandServer server(test_config(), nullptr);
  server.start();
  auto peer = raw_client_in_rawmode(server);
  ASSERT_TRUE(server.wait_for_streaming_clients(1, kPatience));
  protocol::CanFrame frame;
  frame.id = 0x418;
  server.broadcast(frame, 1436509052.249713);
  EXPECT_EQ(peer.read_message(), "< frame 418 1436509052.249713  >");
  peer.send_text("< echo >");
  EXPECT_EQ(peer.read_message(), "< echo >");
}

TEST(SocketcandServer, AnswersMalformedMessagesWithErrors) {
  FrameSink sink;
  SocketcandServer server(test_config(), [&](const protocol::CanFrame& f) { sink.push(f); });
  server.start();
  auto peer = raw_client_in_rawmode(server);
  const std::pair<const char*, const char*> cases[] = {
      {"< bogus >",
       "< error unknown command 'bogus': this server speaks raw mode only (open, rawmode, send, "
       "echo) >"},
      {"< send 180 9 1 2 3 4 5 6 7 8 9 >", "< error send: DLC 9 exceeds 8 (classic CAN) >"},
      {"< send 180 2 zz 01 >", "< error send: data byte 'zz' is not 1-2 hex digits >"},
      {"< send 800 0 >",
       "< error send: identifier 800 exceeds 7FF (an extended identifier has 8 hex digits) >"},
      {"< send 1AAAAAAA 0 >",
       "< error send: extended (29-bit) identifiers are not supported; the rover's bus uses 11-bit "
       "ones >"},
      {"< >", "< error empty message >"},
      {"< open can0 >", "< error unexpected 'open' from a client after the bus was opened >"},
  };
  for (const auto& [input, reply] : cases) {
    peer.send_text(input);
    EXPECT_EQ(peer.read_message(), reply) << input;
  }
  peer.send_text("< send 180 1 01< echo >");
  EXPECT_EQ(peer.read_message(),
            "< error message 'send 180 1 01' was not closed before the next one began >");
  EXPECT_EQ(peer.read_message(), "< echo >");
  peer.send_text("junk< hi >");
  EXPECT_EQ(peer.read_message(), "< error unexpected text 'junk' between messages >");
  EXPECT_EQ(peer.read_message(),
            "< error unexpected 'hi' from a client after the bus was opened >");
  peer.send_text("< send 180 3 3 1 2c >");  // still connected, still working
  ASSERT_EQ(sink.wait_for(1).size(), 1u);
  EXPECT_EQ(server.counters().malformed_messages, 10u);
  EXPECT_EQ(server.counters().frames_from_clients, 1u);
}

TEST(SocketcandServer, CommandsBeforeOpenAreRejected) {
  SocketcandServer server(test_config(), nullptr);
  server.start();
  auto peer = raw_client(server);
  peer.send_text("< rawmode >");
  EXPECT_EQ(peer.read_message(),
            "< error 'rawmode' before the bus is open: send 'open can0' first >");
  peer.send_text("< open can0 >");
  EXPECT_EQ(peer.read_message(), "< ok >");
}

TEST(SocketcandServer, OtherChannelsAreRefusedAndClosed) {
  SocketcandServer server(test_config(), nullptr);
  server.start();
  auto peer = raw_client(server);
  peer.send_text("< open can1 >");
  EXPECT_EQ(peer.read_message(),
            "< error could not open bus 'can1': this server has only 'can0' >");
  EXPECT_TRUE(peer.wait_closed());
  EXPECT_EQ(server.counters().clients_refused, 1u);
}

TEST(SocketcandServer, SilentClientsAreClosedAfterTheHandshakeTimeout) {
  auto config = test_config();
  config.handshake_timeout = milliseconds(50);
  SocketcandServer server(config, nullptr);
  server.start();
  auto peer = raw_client(server);
  EXPECT_EQ(peer.read_message(), "< error no 'open can0' within 50 ms >");
  EXPECT_TRUE(peer.wait_closed());
}

TEST(SocketcandServer, ABrowsersPostIsClosedBeforeItsBodyReachesTheBus) {
  // Any web page can make the operator's browser POST this to 127.0.0.1:29536.
  FrameSink sink;
  SocketcandServer server(test_config(), [&](const protocol::CanFrame& f) { sink.push(f); });
  server.start();
  auto peer = raw_client(server);
  peer.send_text(
      "POST / HTTP/1.1\r\nHost: 127.0.0.1:29536\r\nContent-Type: text/plain\r\n"
      "Content-Length: 48\r\n\r\n< open can0 >< rawmode >< send 180 3 03 01 2C >");
  EXPECT_EQ(peer.read_message(), "< error an HTTP request is not socketcand; closing >");
  EXPECT_TRUE(peer.wait_closed());
  EXPECT_EQ(server.counters().frames_from_clients, 0u);
  EXPECT_EQ(server.counters().clients_refused, 1u);
}

TEST(SocketcandServer, BytesOutsideMessagesBeforeOpenClose) {
  SocketcandServer server(test_config(), nullptr);
  server.start();
  auto peer = raw_client(server);
  peer.send_text("x< open can0 >");
  EXPECT_EQ(peer.read_message(),
            "< error unexpected text 'x' between messages before 'open': closing >");
  EXPECT_TRUE(peer.wait_closed());
}

TEST(SocketcandServer, AnHttpRequestLineAfterOpenCloses) {
  FrameSink sink;
  SocketcandServer server(test_config(), [&](const protocol::CanFrame& f) { sink.push(f); });
  server.start();
  auto peer = raw_client_in_rawmode(server);
  peer.send_text("GET /x HTTP/1.1\r\n\r\n< send 180 1 01 >");
  EXPECT_EQ(peer.read_message(), "< error an HTTP request is not socketcand; closing >");
  EXPECT_TRUE(peer.wait_closed());
  EXPECT_EQ(server.counters().frames_from_clients, 0u);
}

TEST(SocketcandServer, AnIdleOpenedClientIsClosed) {
  auto config = test_config();
  config.idle_timeout = milliseconds(50);
  SocketcandServer server(config, nullptr);
  server.start();
  auto peer = raw_client(server);
  peer.send_text("< open can0 >");
  EXPECT_EQ(peer.read_message(), "< ok >");
  EXPECT_EQ(peer.read_message(), "< error idle for 50 ms: closing >");
  EXPECT_TRUE(peer.wait_closed());
  EXPECT_EQ(server.counters().clients_refused, 1u);
}

TEST(SocketcandServer, RefusesClientsBeyondTheLimit) {
  auto config = test_config();
  config.max_clients = 1;
  SocketcandServer server(config, nullptr);
  server.start();
  auto first = raw_client(server);
  auto second = TcpConnection::connect_loopback(server.port());
  EXPECT_EQ(second.read_message(), "< error too many clients (1): try again later >");
  EXPECT_TRUE(second.wait_closed());
  EXPECT_EQ(server.counters().clients_refused, 1u);
}

TEST(SocketcandServer, BroadcastsToEveryClientAndRelaysBetweenThem) {
  SocketcandServer server(test_config(), nullptr);
  server.start();
  SocketcandClient a(client_config(server));
  SocketcandClient b(client_config(server));
  ASSERT_TRUE(server.wait_for_streaming_clients(2, kPatience));
  protocol::CanFrame frame;
  frame.id = 0x400;
  frame.dlc = 1;
  frame.data[0] = 0xC1;
  server.broadcast(frame, 1.0);
  EXPECT_EQ(receive_frames(a, 1), std::vector<protocol::CanFrame>{frame});
  EXPECT_EQ(receive_frames(b, 1), std::vector<protocol::CanFrame>{frame});
  frame.id = 0x410;
  a.send(frame);  // every node on a bus sees every frame, except its own
  EXPECT_EQ(receive_frames(b, 1), std::vector<protocol::CanFrame>{frame});
  EXPECT_TRUE(a.receive(milliseconds(50)).empty());
}

TEST(SocketcandServer, GraceHoldsFramesUntilTheClientSpeaks) {
  auto config = test_config();
  config.rawmode_grace = std::chrono::minutes(1);
  SocketcandServer server(config, nullptr);
  server.start();
  auto peer = raw_client_in_rawmode(server);
  EXPECT_FALSE(server.wait_for_streaming_clients(1, milliseconds(20)));
  peer.send_text("< echo >");
  EXPECT_EQ(peer.read_message(), "< echo >");
  EXPECT_TRUE(server.wait_for_streaming_clients(1, kPatience));
}

TEST(SocketcandServer, CallbackExceptionsBecomeErrorReplies) {
  SocketcandServer server(test_config(), [](const protocol::CanFrame&) {
    throw std::runtime_error("µ9 does not exist");
  });
  server.start();
  auto peer = raw_client_in_rawmode(server);
  peer.send_text("< send 490 0 >");
  EXPECT_EQ(peer.read_message(),
            "< error send: frame rejected by the simulator: ??9 does not exist >");
}

TEST(SocketcandServer, ClientThatNeverReadsCostsBoundedMemory) {
  auto config = test_config();
  config.max_queued_bytes = 4096;
  SocketcandServer server(config, nullptr);
  server.start();
  auto peer = raw_client_in_rawmode(server);  // and never reads again
  ASSERT_TRUE(server.wait_for_streaming_clients(1, kPatience));
  protocol::CanFrame frame;
  frame.id = 0x188;
  frame.dlc = 8;
  for (int i = 0; i < 1000000 && server.counters().frames_dropped == 0; ++i)
    server.broadcast(frame, 1.0);
  EXPECT_GT(server.counters().frames_dropped, 0u);
  server.stop();  // still stops promptly
}

TEST(SocketcandServer, StopClosesEveryConnection) {
  SocketcandServer server(test_config(), nullptr);
  server.start();
  auto peer = raw_client_in_rawmode(server);
  SocketcandClient client(client_config(server));
  server.stop();
  server.stop();  // idempotent
  EXPECT_TRUE(peer.wait_closed());
  EXPECT_THROW(receive_frames(client, 1), TransportError);
  protocol::CanFrame frame;
  server.broadcast(frame, 0.0);  // ignored once stopped
}

TEST(SocketcandServer, ListenErrorsAreClear) {
  SocketcandServer first(test_config(), nullptr);
  first.start();
  auto config = test_config();
  config.port = first.port();
  SocketcandServer second(config, nullptr);
  try {
    second.start();
    FAIL() << "two servers listen on one port";
  } catch (const TransportError& e) {
    EXPECT_NE(std::string(e.what()).find("another marsokhod sim or socketcand listens there"),
              std::string::npos)
        << e.what();
  }
  config.address = "localhost";
  SocketcandServer third(config, nullptr);
  EXPECT_THROW(third.start(), TransportError);
}

TEST(SocketcandServer, BroadcastRejectsWhatTheWireCannotCarry) {
  SocketcandServer server(test_config(), nullptr);
  server.start();
  protocol::CanFrame frame;
  frame.id = 0x800;
  EXPECT_THROW(server.broadcast(frame, 0.0), std::invalid_argument);
  frame.id = 0x180;
  EXPECT_THROW(server.broadcast(frame, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::bus
