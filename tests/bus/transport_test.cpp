#include "bus/transport.hpp"

#include <gtest/gtest.h>

#include "tcp_test_peer.hpp"

namespace marsokhod::bus {
namespace {

std::string error_of(const std::string& url) {
  try {
    parse_transport_url(url);
  } catch (const TransportError& e) {
    return e.what();
  }
  ADD_FAILURE() << url << " was accepted";
  return "";
}

TEST(TransportUrl, SocketCan) {
  const TransportUrl url = parse_transport_url("socketcan:can0");
  EXPECT_EQ(url.kind, TransportUrl::Kind::kSocketCan);
  EXPECT_EQ(url.interface, "can0");
}

TEST(TransportUrl, SocketcandWithDefaults) {
  const TransportUrl url = parse_transport_url("socketcand://rover.local");
  EXPECT_EQ(url.kind, TransportUrl::Kind::kSocketcand);
  EXPECT_EQ(url.host, "rover.local");
  EXPECT_EQ(url.port, 29536);
  EXPECT_EQ(url.channel, "can0");
}

TEST(TransportUrl, SocketcandWithEverything) {
  const TransportUrl url = parse_transport_url("socketcand://127.0.0.1:4000/vcan1");
  EXPECT_EQ(url.host, "127.0.0.1");
  EXPECT_EQ(url.port, 4000);
  EXPECT_EQ(url.channel, "vcan1");
  const TransportUrl v6 = parse_transport_url("socketcand://[::1]:29537/can0");
  EXPECT_EQ(v6.host, "::1");
  EXPECT_EQ(v6.port, 29537);
  EXPECT_EQ(parse_transport_url("socketcand://[::1]").port, 29536);
}

TEST(TransportUrl, MalformedUrlsSayWhatIsExpected) {
  const std::string forms =
      "; expected 'socketcan:IFACE' (e.g. socketcan:can0) or 'socketcand://HOST[:PORT][/CHANNEL]' "
      "(e.g. socketcand://127.0.0.1:29536/can0)";
  EXPECT_EQ(error_of(""), "bad transport URL '': unknown transport" + forms);
  EXPECT_EQ(error_of("can0"), "bad transport URL 'can0': unknown transport" + forms);
  EXPECT_EQ(
      error_of("socketcan:"),
      "bad transport URL 'socketcan:': interface '' is not an interface name (1-15 characters, "
      "no '/', ':' or spaces)" +
          forms);
  EXPECT_EQ(
      error_of("socketcan:averyverylongname0"),
      "bad transport URL 'socketcan:averyverylongname0': interface 'averyverylongname0' is not an "
      "interface name (1-15 characters, no '/', ':' or spaces)" +
          forms);
  EXPECT_EQ(error_of("socketcand://"), "bad transport URL 'socketcand://': no host" + forms);
  EXPECT_EQ(error_of("socketcand://:29536/can0"),
            "bad transport URL 'socketcand://:29536/can0': no host" + forms);
  EXPECT_EQ(error_of("socketcand://host:/can0"),
            "bad transport URL 'socketcand://host:/can0': empty port after ':'" + forms);
  EXPECT_EQ(
      error_of("socketcand://host:http/can0"),
      "bad transport URL 'socketcand://host:http/can0': port 'http' is not a number in 1..65535" +
          forms);
  EXPECT_EQ(
      error_of("socketcand://host:70000"),
      "bad transport URL 'socketcand://host:70000': port '70000' is not a number in 1..65535" +
          forms);
  EXPECT_EQ(
      error_of("socketcand://host:0"),
      "bad transport URL 'socketcand://host:0': port '0' is not a number in 1..65535" + forms);
  EXPECT_EQ(
      error_of("socketcand://host/"),
      "bad transport URL 'socketcand://host/': channel '' is not a bus name (1-16 characters, no "
      "'/', ':', '<', '>' or spaces)" +
          forms);
  EXPECT_EQ(
      error_of("socketcand://host/can0/x"),
      "bad transport URL 'socketcand://host/can0/x': channel 'can0/x' is not a bus name (1-16 "
      "characters, no '/', ':', '<', '>' or spaces)" +
          forms);
  EXPECT_EQ(error_of("socketcand://[::1/can0"),
            "bad transport URL 'socketcand://[::1/can0': IPv6 host has no closing ']'" + forms);
}

TEST(OpenTransport, RefusedConnectionIsAClearError) {
  const std::uint16_t port = testing::unused_port();
  try {
    open_transport("socketcand://127.0.0.1:" + std::to_string(port) + "/can0");
    FAIL() << "connected to a port nobody listens on";
  } catch (const TransportError& e) {
    EXPECT_EQ(
        std::string(e.what()),
        "cannot connect to socketcand at 127.0.0.1:" + std::to_string(port) +
            ": Connection refused: is `marsokhod sim` (or socketcand) running and listening on "
            "that port?");
  }
}

TEST(OpenTransport, DescribesFrames) {
  protocol::CanFrame frame;
  frame.id = 0x180;
  frame.dlc = 3;
  EXPECT_EQ(describe_frame(frame), "id 0x180, DLC 3");
}

}  // namespace
}  // namespace marsokhod::bus
