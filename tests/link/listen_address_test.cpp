// parse_listen_address: the forms --listen takes, and errors that say what to write instead.
#include "link/listen_address.hpp"

#include <gtest/gtest.h>

#include <string>

namespace marsokhod::link {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_listen_address(text);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  ADD_FAILURE() << "accepted: " << text;
  return {};
}

TEST(ListenAddress, DefaultsToLoopbackPort8080) {
  const ListenAddress listen;
  EXPECT_EQ(to_string(listen), "127.0.0.1:8080");
}

TEST(ListenAddress, ParsesIpv4AndBracketedIpv6) {
  const ListenAddress v4 = parse_listen_address("0.0.0.0:80");
  EXPECT_EQ(v4.address, "0.0.0.0");
  EXPECT_EQ(v4.port, 80);
  const ListenAddress v6 = parse_listen_address("[::1]:65535");
  EXPECT_EQ(v6.address, "::1");
  EXPECT_EQ(v6.port, 65535);
  EXPECT_EQ(parse_listen_address("127.0.0.1:0").port, 0);
  for (const char* text : {"127.0.0.1:8080", "[::1]:8080", "0.0.0.0:1"}) {
    EXPECT_EQ(to_string(parse_listen_address(text)), text);
  }
}

TEST(ListenAddress, RejectsWithAnExample) {
  for (const char* text : {"8080", "127.0.0.1", "127.0.0.1:", ":8080", "localhost:8080",
                           "127.0.0.1:65536", "127.0.0.1:-1", "127.0.0.1:80x", "::1:8080",
                           "[]:8080", "256.0.0.1:8080"}) {
    const std::string error = error_of(text);
    EXPECT_NE(error.find(text), std::string::npos) << error;
    EXPECT_NE(error.find("e.g. 127.0.0.1:8080"), std::string::npos) << error;
  }
  EXPECT_NE(error_of("127.0.0.1:99999").find("0..65535"), std::string::npos);
  EXPECT_NE(error_of("rover:8080").find("not an IP address"), std::string::npos);
}

}  // namespace
}  // namespace marsokhod::link
