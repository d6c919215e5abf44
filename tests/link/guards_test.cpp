// The link's pure guards: stale input, the rate limit, Host and Origin, cookies, the wrong-token
// back-off, session ids, the token file. Time is a value here.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "link/access_token.hpp"
#include "link/auth_guard.hpp"
#include "link/input_freshness.hpp"
#include "link/request_guard.hpp"

namespace marsokhod::link {
namespace {

TEST(InputFreshness, DropsRepeatedAndEarlierSequenceNumbers) {
  InputFreshness freshness(0.25);
  EXPECT_FALSE(freshness.check({5, 1000.0}, 100.0));
  const auto repeated = freshness.check({5, 1050.0}, 100.05);
  ASSERT_TRUE(repeated);
  EXPECT_EQ(*repeated, "seq 5 is not after 5: out of order or repeated");
  EXPECT_TRUE(freshness.check({4, 1100.0}, 100.1));
  EXPECT_FALSE(freshness.check({6, 1150.0}, 100.15));
}

TEST(InputFreshness, DropsABurstHeldUpInAStall) {
  // Sent every 50 ms; the network stalls 2 s, then delivers everything at once.
  InputFreshness freshness(0.25);
  std::uint64_t seq = 0;
  for (int k = 0; k < 10; ++k) {
    EXPECT_FALSE(freshness.check({++seq, 50.0 * k}, 10.0 + 0.05 * k + 0.002)) << k;
  }
  int passed = 0;
  for (int k = 10; k < 50; ++k) {  // sent at 0.5 … 2.45 s, all arriving at 2.5 s
    if (!freshness.check({++seq, 50.0 * k}, 12.5)) ++passed;
  }
  EXPECT_EQ(passed, 5);  // only those sent within 0.25 s of the arrival: 2.25 … 2.45 s
  EXPECT_FALSE(freshness.check({++seq, 2500.0}, 12.502));
}

TEST(InputFreshness, ToleratesJitterAndSlowClockDrift) {
  InputFreshness freshness(0.25);
  EXPECT_FALSE(freshness.check({1, 0.0}, 0.010));
  EXPECT_FALSE(freshness.check({2, 50.0}, 0.250));  // 190 ms of jitter: allowed
  // The console's clock runs 100 ppm slow for an hour: its messages look later and later.
  EXPECT_FALSE(freshness.check({3, 3600e3 * (1.0 - 1e-4)}, 3600.010));
}

TEST(TokenBucket, AllowsTheBurstThenTheRate) {
  TokenBucket bucket(10.0, 3.0);
  EXPECT_TRUE(bucket.take(0.0));
  EXPECT_TRUE(bucket.take(0.0));
  EXPECT_TRUE(bucket.take(0.0));
  EXPECT_FALSE(bucket.take(0.0));
  EXPECT_FALSE(bucket.take(0.05));  // half a token
  EXPECT_TRUE(bucket.take(0.1));
  EXPECT_TRUE(bucket.take(10.0));  // refilled, but never beyond the burst
  EXPECT_TRUE(bucket.take(10.0));
  EXPECT_TRUE(bucket.take(10.0));
  EXPECT_FALSE(bucket.take(10.0));
}

TEST(RequestGuard, HostsOfALoopbackServer) {
  const OriginPolicy policy = origin_policy("127.0.0.1", 8080, {"Rover.Local"}, {});
  for (const char* host : {"127.0.0.1", "127.0.0.1:8080", "localhost", "localhost.:8080",
                           "[::1]:8080", "rover.local", "ROVER.LOCAL:80"}) {
    EXPECT_TRUE(host_allowed(host, policy)) << host;
  }
  for (const char* host : {"", "evil.example", "10.0.0.7", "localhost.evil.example", "[::1",
                           "localhost:99999", "localhost:", "local host", "127.0.0.1:80/x"}) {
    EXPECT_FALSE(host_allowed(host, policy)) << host;
  }
}

TEST(RequestGuard, AnyIpLiteralWhenListeningOnEveryInterface) {
  const OriginPolicy policy = origin_policy("0.0.0.0", 8080, {}, {});
  EXPECT_TRUE(host_allowed("10.0.0.7:8080", policy));
  EXPECT_TRUE(host_allowed("[fe80::1]:8080", policy));
  EXPECT_FALSE(host_allowed("rover.evil.example:8080", policy));  // a name can be rebound
}

TEST(RequestGuard, Origins) {
  const OriginPolicy policy = origin_policy("127.0.0.1", 8080, {}, {"https://Proxy.Example"});
  EXPECT_TRUE(origin_allowed("http://127.0.0.1:8080", policy));
  EXPECT_TRUE(origin_allowed("http://localhost:8080", policy));
  EXPECT_TRUE(origin_allowed("https://proxy.example", policy));
  EXPECT_FALSE(origin_allowed("http://127.0.0.1:8081", policy));  // another local server
  EXPECT_FALSE(origin_allowed("http://127.0.0.1", policy));       // port 80
  EXPECT_FALSE(origin_allowed("https://127.0.0.1:8080", policy));
  EXPECT_FALSE(origin_allowed("null", policy));
  EXPECT_FALSE(origin_allowed("http://evil.example:8080", policy));
  EXPECT_NO_THROW(validate_origin("https://proxy.example:8443"));
  EXPECT_THROW(validate_origin("proxy.example"), std::invalid_argument);
  EXPECT_THROW(validate_origin("ftp://proxy.example"), std::invalid_argument);
  EXPECT_NO_THROW(validate_host_name("rover.local"));
  EXPECT_THROW(validate_host_name("rover.local:8080"), std::invalid_argument);
  EXPECT_THROW(validate_host_name("http://rover"), std::invalid_argument);
}

TEST(RequestGuard, CookieAndBearer) {
  EXPECT_EQ(cookie_value("a=1; s_8080=abc; b=2", "s_8080"), "abc");
  EXPECT_EQ(cookie_value("s_8080=abc", "s_8080"), "abc");
  EXPECT_FALSE(cookie_value("xs_8080=abc", "s_8080"));
  EXPECT_FALSE(cookie_value("", "s_8080"));
  EXPECT_EQ(bearer_token("Bearer tok"), "tok");
  EXPECT_FALSE(bearer_token("Basic dG9r"));
}

TEST(AuthThrottle, DoublesTheWaitAndForgetsOnSuccess) {
  AuthThrottle throttle(1.0, 4.0, 8);
  EXPECT_EQ(throttle.wait_s("10.0.0.1", 0.0), 0.0);
  EXPECT_EQ(throttle.failed("10.0.0.1", 0.0).delay_s, 1.0);
  EXPECT_EQ(throttle.wait_s("10.0.0.1", 0.5), 0.5);
  EXPECT_EQ(throttle.wait_s("10.0.0.2", 0.5), 0.0);  // per address
  EXPECT_EQ(throttle.failed("10.0.0.1", 1.0).delay_s, 2.0);
  EXPECT_EQ(throttle.failed("10.0.0.1", 3.0).delay_s, 4.0);
  const auto capped = throttle.failed("10.0.0.1", 7.0);
  EXPECT_EQ(capped.delay_s, 4.0);
  EXPECT_EQ(capped.in_a_row, 4);
  throttle.succeeded("10.0.0.1");
  EXPECT_EQ(throttle.wait_s("10.0.0.1", 7.0), 0.0);
}

TEST(AuthThrottle, StaysBoundedInAddresses) {
  AuthThrottle throttle(100.0, 100.0, 4);
  for (int i = 0; i < 100; ++i) throttle.failed("10.0.0." + std::to_string(i), 0.0);
  int waiting = 0;
  for (int i = 0; i < 100; ++i) waiting += throttle.wait_s("10.0.0." + std::to_string(i), 1.0) > 0;
  EXPECT_EQ(waiting, 4);
}

TEST(SessionStore, RandomIdsAndTheOldestGoesWhenFull) {
  SessionStore store(2);
  const std::string a = store.create();
  const std::string b = store.create();
  EXPECT_EQ(a.size(), 32U);
  EXPECT_NE(a, b);
  EXPECT_TRUE(store.valid(a));
  EXPECT_FALSE(store.valid(std::string(32, '0')));
  const std::string c = store.create();
  EXPECT_FALSE(store.valid(a));
  EXPECT_TRUE(store.valid(b));
  EXPECT_TRUE(store.valid(c));
}

TEST(AccessToken, GetrandomTokensDiffer) {
  std::set<std::string> tokens;
  for (int i = 0; i < 50; ++i) tokens.insert(generate_token());
  EXPECT_EQ(tokens.size(), 50U);
  EXPECT_EQ(random_hex(3).size(), 6U);
}

TEST(AccessToken, ATokenFileMustBeTheOwnersOnly) {
  const auto file = std::filesystem::temp_directory_path() /
                    ("marsokhod-token-" + std::to_string(::getpid()));
  std::ofstream(file) << "  file-token-0123456789  \n second line\n";
  ::chmod(file.c_str(), 0600);
  EXPECT_EQ(read_token_file(file), "file-token-0123456789");
  ::chmod(file.c_str(), 0644);
  try {
    read_token_file(file);
    ADD_FAILURE() << "a world-readable token file was read";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("mode 0644"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("chmod 600"), std::string::npos) << e.what();
  }
  ::chmod(file.c_str(), 0600);
  std::ofstream(file) << "short\n";
  EXPECT_THROW(read_token_file(file), std::invalid_argument);
  std::filesystem::remove(file);
  EXPECT_THROW(read_token_file(file), std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::link
