#include "bus/socketcand_client.hpp"

#include <gtest/gtest.h>

#include "tcp_test_peer.hpp"

namespace marsokhod::bus {
namespace {

using std::chrono::milliseconds;
using testing::ScriptedServer;
using testing::TcpConnection;

SocketcandClient::Config config_for(std::uint16_t port, const std::string& channel = "can0") {
  SocketcandClient::Config config;
  config.port = port;
  config.channel = channel;
  config.handshake_timeout = milliseconds(300);
  return config;
}

std::string connect_error(const SocketcandClient::Config& config) {
  try {
    SocketcandClient client(config);
  } catch (const TransportError& e) {
    return e.what();
  }
  ADD_FAILURE() << "the handshake succeeded";
  return "";
}

protocol::CanFrame control_request() {  // µ3, drv = eim = 1, pwm = 300: 180#03012C
  protocol::CanFrame frame;
  frame.id = 0x180;
  frame.dlc = 3;
  frame.data = {0x03, 0x01, 0x2C};
  return frame;
}

TEST(SocketcandClient, HandshakesAndSendsInSocketcandFormat) {
  std::optional<std::string> sent;
  {
    ScriptedServer server([&](TcpConnection& peer) {
      if (!testing::serve_handshake(peer, "vcan1")) return;
      sent = peer.read_message();
    });
    SocketcandClient client(config_for(server.port(), "vcan1"));
    EXPECT_EQ(client.name(), "socketcand://127.0.0.1:" + std::to_string(server.port()) + "/vcan1");
    client.send(control_request());
    EXPECT_EQ(client.counters().frames_sent, 1u);
  }
  EXPECT_EQ(sent, "< send 180 3 03 01 2C >");
}

TEST(SocketcandClient, ReceivesFramesAndCountsWhatItDrops) {
  ScriptedServer server([](TcpConnection& peer) {
    if (!testing::serve_handshake(peer)) return;
    peer.send_text("< frame 180 1.000000 03012C >< frame 180 1.0 0G >< frame 1AAAAAAA 1.0 01 >");
    peer.send_text("stray< error no such bus >< fdframe 123 00 1.0 11 >< echo >< frame 418 2.0");
    peer.send_text("00000  >");  // the end of a frame split across two writes
    peer.wait_closed();
  });
  SocketcandClient client(config_for(server.port()));
  std::vector<protocol::CanFrame> frames;
  for (int i = 0; i < 50 && frames.size() < 2; ++i) {
    for (const auto& f : client.receive(milliseconds(100))) frames.push_back(f);
  }
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0], control_request());
  EXPECT_EQ(frames[1].id, 0x418u);
  EXPECT_EQ(frames[1].dlc, 0);
  const TransportCounters counters = client.counters();
  EXPECT_EQ(counters.frames_received, 2u);
  EXPECT_EQ(counters.malformed_dropped, 2u);  // the bad hex and the stray text
  EXPECT_EQ(counters.ignored, 2u);            // the extended frame and the fdframe
  EXPECT_EQ(counters.peer_errors, 1u);
  EXPECT_EQ(client.last_peer_error(), "no such bus");
}

TEST(SocketcandClient, ReceiveWaitsNoLongerThanItsTimeout) {
  ScriptedServer server([](TcpConnection& peer) {
    if (testing::serve_handshake(peer)) peer.wait_closed();
  });
  SocketcandClient client(config_for(server.port()));
  const auto start = std::chrono::steady_clock::now();
  EXPECT_TRUE(client.receive(milliseconds(30)).empty());
  const auto waited = std::chrono::steady_clock::now() - start;
  EXPECT_GE(waited, milliseconds(29));
  EXPECT_LT(waited, milliseconds(2000));
}

TEST(SocketcandClient, ServerClosingIsAnError) {
  ScriptedServer server([](TcpConnection& peer) { testing::serve_handshake(peer); });
  SocketcandClient client(config_for(server.port()));
  EXPECT_THROW(
      {
        for (int i = 0; i < 50; ++i) client.receive(milliseconds(100));
      },
      TransportError);
  EXPECT_THROW(client.send(control_request()), TransportError);  // and it stays broken
}

TEST(SocketcandClient, BadGreetingIsRejected) {
  ScriptedServer server([](TcpConnection& peer) {
    peer.send_text("< hello >");
    peer.wait_closed();
  });
  const auto port = std::to_string(server.port());
  EXPECT_EQ(
      connect_error(config_for(server.port())),
      "socketcand at 127.0.0.1:" + port +
          " answered the connection with '< hello >' instead of the greeting '< hi >': is it a "
          "socketcand server?");
}

TEST(SocketcandClient, NonSocketcandPeerIsRejected) {
  ScriptedServer server([](TcpConnection& peer) {
    peer.send_text("HTTP/1.1 400 Bad Request\r\n\r\n");
    peer.wait_closed();
  });
  EXPECT_NE(connect_error(config_for(server.port()))
                .find("unparseable data (unexpected text 'HTTP/1.1 400"),
            std::string::npos);
}

TEST(SocketcandClient, SilentServerTimesOut) {
  ScriptedServer server([](TcpConnection& peer) { peer.wait_closed(); });
  EXPECT_EQ(connect_error(config_for(server.port())),
            "socketcand at 127.0.0.1:" + std::to_string(server.port()) +
                " did not send the greeting '< hi >' within 300 ms: is it a socketcand server?");
}

TEST(SocketcandClient, RefusedChannelIsReported) {
  ScriptedServer server([](TcpConnection& peer) {
    peer.send_text("< hi >");
    if (peer.read_message() == std::optional<std::string>("< open can1 >")) {
      peer.send_text("< error could not open bus >");
    }
    peer.wait_closed();
  });
  EXPECT_EQ(connect_error(config_for(server.port(), "can1")),
            "socketcand at 127.0.0.1:" + std::to_string(server.port()) +
                " refused opening channel 'can1': could not open bus");
}

TEST(SocketcandClient, TheServersWordsAreEscapedInErrors) {
  // A hostile server's reply must not put terminal control sequences into our messages.
  ScriptedServer server([](TcpConnection& peer) {
    peer.send_text("< hi >");
    if (peer.read_message()) peer.send_text("< error \x1b]0;owned\x07\x1b[2J >");
    peer.wait_closed();
  });
  const std::string error = connect_error(config_for(server.port(), "can0"));
  EXPECT_EQ(error.find('\x1b'), std::string::npos) << error;
  EXPECT_EQ(error.find('\x07'), std::string::npos) << error;
  EXPECT_NE(error.find("\\x1b]0;owned\\x07\\x1b[2J"), std::string::npos) << error;
}

TEST(SocketcandClient, ConnectionRefusedIsAClearError) {
  const std::uint16_t port = testing::unused_port();
  EXPECT_EQ(connect_error(config_for(port)),
            "cannot connect to socketcand at 127.0.0.1:" + std::to_string(port) +
                ": Connection refused: is `marsokhod sim` (or socketcand) running and listening on "
                "that port?");
}

TEST(SocketcandClient, InvalidChannelIsRejectedBeforeConnecting) {
  EXPECT_NE(connect_error(config_for(testing::unused_port(), "can 0")).find("is not a bus name"),
            std::string::npos);
}

TEST(SocketcandClient, InvalidFramesAreNotSent) {
  ScriptedServer server([](TcpConnection& peer) {
    if (testing::serve_handshake(peer)) peer.wait_closed(milliseconds(1000));
  });
  SocketcandClient client(config_for(server.port()));
  protocol::CanFrame frame = control_request();
  frame.dlc = 9;
  EXPECT_THROW(client.send(frame), TransportError);
  frame.dlc = 3;
  frame.id = 0x800;
  EXPECT_THROW(client.send(frame), TransportError);
  EXPECT_EQ(client.counters().frames_sent, 0u);
}

}  // namespace
}  // namespace marsokhod::bus
