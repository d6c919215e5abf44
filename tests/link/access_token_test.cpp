// The WebSocket token: its form, its comparison, and finding it in a request target.
#include "link/access_token.hpp"

#include <gtest/gtest.h>

#include <set>

namespace marsokhod::link {
namespace {

TEST(AccessToken, Generates128BitsAsHex) {
  std::set<std::string> seen;
  for (int i = 0; i < 8; ++i) {
    const std::string token = generate_token();
    EXPECT_EQ(token.size(), 32U);
    EXPECT_EQ(token.find_first_not_of("0123456789abcdef"), std::string::npos) << token;
    EXPECT_NO_THROW(validate_token(token));
    seen.insert(token);
  }
  EXPECT_EQ(seen.size(), 8U);
}

TEST(AccessToken, ValidatesGivenTokens) {
  EXPECT_NO_THROW(validate_token("rover-console.2024_~"));
  EXPECT_THROW(validate_token("short"), std::invalid_argument);
  EXPECT_THROW(validate_token("has a space in it!"), std::invalid_argument);
  EXPECT_THROW(validate_token("0123456789abcdef&x=1"), std::invalid_argument);
}

TEST(AccessToken, ComparesExactly) {
  EXPECT_TRUE(tokens_equal("0123456789abcdef", "0123456789abcdef"));
  EXPECT_FALSE(tokens_equal("0123456789abcdef", "0123456789abcdeF"));
  EXPECT_FALSE(tokens_equal("0123456789abcdef", "0123456789abcde"));
  EXPECT_FALSE(tokens_equal("", "x"));
}

TEST(AccessToken, FindsQueryParameters) {
  EXPECT_EQ(query_parameter("/ws?token=abc", "token"), "abc");
  EXPECT_EQ(query_parameter("/ws?x=1&token=abc&y=2", "token"), "abc");
  EXPECT_EQ(query_parameter("/ws?token=abc#frag", "token"), "abc");
  EXPECT_EQ(query_parameter("/ws?token=", "token"), "");
  EXPECT_EQ(query_parameter("/ws?token", "token"), "");
  EXPECT_FALSE(query_parameter("/ws", "token").has_value());
  EXPECT_FALSE(query_parameter("/ws?tokens=abc", "token").has_value());
  EXPECT_FALSE(query_parameter("/ws?x=token=abc", "token").has_value());
  EXPECT_EQ(target_path("/ws?token=abc"), "/ws");
  EXPECT_EQ(target_path("/index.html#top"), "/index.html");
}

}  // namespace
}  // namespace marsokhod::link
