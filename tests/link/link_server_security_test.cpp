// The server as a hostile page or client meets it: Host (DNS rebinding) and Origin (cross-site
// WebSocket hijacking) checks, the token traded for an HttpOnly SameSite=Strict cookie, the
// security headers, and the connection limits. Loopback only; every wait has a deadline.
#include "link/link_server.hpp"

#include <gtest/gtest.h>

#include <boost/asio/read.hpp>
#include <boost/asio/write.hpp>

#include "test_client.hpp"

namespace marsokhod::link {
namespace {

namespace http = testing::http;
using testing::Headers;
using testing::TestClient;

constexpr const char* kToken = "security-token-0123456789";

class LinkServerSecurityTest : public ::testing::Test {
 protected:
  void start(ServerOptions options = {}) {
    options.listen = {"127.0.0.1", 0};
    options.token = kToken;
    options.auth_backoff_first_s = 60.0;
    server_ = std::make_unique<LinkServer>(Params{}, std::move(options));
    server_->start();
  }
  std::string own_origin() const { return "http://127.0.0.1:" + std::to_string(server_->port()); }
  http::response<http::string_body> request(http::verb method, const std::string& target,
                                            const Headers& headers = {}) {
    return testing::http_request(server_->port(), method, target, headers);
  }
  // POST /session with the token; the cookie's "name=value", or "" when refused.
  std::string session_cookie() {
    const auto response = request(http::verb::post, "/session",
                                  {{"Authorization", std::string("Bearer ") + kToken},
                                   {"Origin", own_origin()}});
    EXPECT_EQ(response.result_int(), 204);
    const std::string set_cookie(response[http::field::set_cookie]);
    return set_cookie.substr(0, set_cookie.find(';'));
  }

  std::unique_ptr<LinkServer> server_;
};

TEST_F(LinkServerSecurityTest, AForeignHostIsRefusedWith403) {
  start();
  for (const char* host : {"evil.example", "evil.example:8080", "127.0.0.1.evil.example"}) {
    EXPECT_EQ(request(http::verb::get, "/", {{"Host", host}}).result_int(), 403) << host;
    TestClient client(server_->port(), "/ws",
                      {{"Host", host}, {"Authorization", std::string("Bearer ") + kToken}});
    EXPECT_FALSE(client.open()) << host;
    EXPECT_EQ(client.handshake_response().result_int(), 403) << host;
  }
  for (const char* host : {"127.0.0.1", "localhost:8080", "LOCALHOST", "[::1]:80"}) {
    EXPECT_EQ(request(http::verb::get, "/", {{"Host", host}}).result_int(), 404) << host;  // no files
  }
  EXPECT_EQ(server_->stats().forbidden, 6U);
}

TEST_F(LinkServerSecurityTest, ConfiguredHostsAndOriginsAreAllowed) {
  ServerOptions options;
  options.allowed_hosts = {"rover.local"};
  options.allowed_origins = {"https://proxy.example"};
  start(options);
  EXPECT_EQ(request(http::verb::get, "/", {{"Host", "rover.local:8080"}}).result_int(), 404);
  TestClient client(server_->port(), "/ws",
                    {{"Origin", "https://proxy.example"},
                     {"Authorization", std::string("Bearer ") + kToken}});
  EXPECT_TRUE(client.open()) << client.handshake_response().result_int();
}

TEST_F(LinkServerSecurityTest, AWebSocketFromAForeignOriginIsRefusedWith403) {
  start();
  const std::string port = std::to_string(server_->port());
  for (const std::string& origin :
       {std::string("http://evil.example"), std::string("null"), "http://127.0.0.1:1" + port,
        "https://127.0.0.1:" + port}) {
    TestClient client(server_->port(), "/ws",
                      {{"Origin", origin}, {"Authorization", std::string("Bearer ") + kToken}});
    EXPECT_FALSE(client.open()) << origin;
    EXPECT_EQ(client.handshake_response().result_int(), 403) << origin;
  }
  for (const std::string& origin : {own_origin(), "http://localhost:" + port}) {
    TestClient client(server_->port(), "/ws",
                      {{"Origin", origin}, {"Authorization", std::string("Bearer ") + kToken}});
    EXPECT_TRUE(client.open()) << origin;
  }
}

TEST_F(LinkServerSecurityTest, TheTokenIsTradedForAnHttpOnlyStrictCookie) {
  start();
  const auto response = request(http::verb::post, "/session",
                                {{"Authorization", std::string("Bearer ") + kToken}});
  ASSERT_EQ(response.result_int(), 204);
  const std::string set_cookie(response[http::field::set_cookie]);
  const std::string name = "marsokhod_session_" + std::to_string(server_->port()) + "=";
  EXPECT_EQ(set_cookie.rfind(name, 0), 0U) << set_cookie;
  EXPECT_NE(set_cookie.find("; HttpOnly"), std::string::npos) << set_cookie;
  EXPECT_NE(set_cookie.find("; SameSite=Strict"), std::string::npos) << set_cookie;
  EXPECT_EQ(set_cookie.find(kToken), std::string::npos) << "the cookie is not the token";
  const std::string cookie = session_cookie();
  TestClient client(server_->port(), "/ws", {{"Cookie", "other=1; " + cookie}});
  ASSERT_TRUE(client.open());
  EXPECT_EQ(client.receive_type("hello").value_or(nlohmann::json{})["type"], "hello");
  TestClient forged(server_->port(), "/ws", {{"Cookie", name + std::string(32, '0')}});
  EXPECT_EQ(forged.handshake_response().result_int(), 401);
}

TEST_F(LinkServerSecurityTest, ASessionNeedsPostTheRightTokenAndOurOrigin) {
  start();
  EXPECT_EQ(request(http::verb::get, "/session").result_int(), 405);
  EXPECT_EQ(request(http::verb::post, "/session",
                    {{"Origin", "http://evil.example"},
                     {"Authorization", std::string("Bearer ") + kToken}})
                .result_int(),
            403);
  const auto wrong = request(http::verb::post, "/session",
                             {{"Authorization", "Bearer wrong-token-0123456789"}});
  EXPECT_EQ(wrong.result_int(), 401);
  EXPECT_TRUE(wrong[http::field::set_cookie].empty());
  EXPECT_EQ(request(http::verb::post, "/session",
                    {{"Authorization", std::string("Bearer ") + kToken}})
                .result_int(),
            429);  // backing off after the wrong one
}

TEST_F(LinkServerSecurityTest, EveryResponseCarriesTheSecurityHeaders) {
  start();
  for (const auto& response :
       {request(http::verb::get, "/"), request(http::verb::get, "/", {{"Host", "evil.example"}}),
        request(http::verb::post, "/session")}) {
    EXPECT_EQ(response["X-Content-Type-Options"], "nosniff") << response.result_int();
    EXPECT_EQ(response["Referrer-Policy"], "no-referrer") << response.result_int();
    const std::string csp(response["Content-Security-Policy"]);
    EXPECT_NE(csp.find("frame-ancestors 'none'"), std::string::npos) << csp;
    EXPECT_NE(csp.find("default-src 'self'"), std::string::npos) << csp;
  }
}

TEST_F(LinkServerSecurityTest, ConnectionsBeyondTheCapAreClosedAtOnce) {
  ServerOptions options;
  options.max_connections = 2;
  start(options);
  boost::asio::io_context io;
  std::vector<boost::asio::ip::tcp::socket> held;
  for (int i = 0; i < 2; ++i) {
    held.emplace_back(io);
    held.back().connect(testing::loopback(server_->port()));
  }
  // The server counts a connection once it accepted it: wait until both are (bounded).
  const auto deadline = std::chrono::steady_clock::now() + testing::kWait;
  while (server_->stats().connections_refused == 0 && std::chrono::steady_clock::now() < deadline) {
    boost::asio::ip::tcp::socket extra(io);
    extra.connect(testing::loopback(server_->port()));
    boost::system::error_code error;
    char byte = 0;
    boost::asio::write(extra, boost::asio::buffer("GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n"),
                       error);
    boost::asio::read(extra, boost::asio::buffer(&byte, 1), error);
    if (error == boost::asio::error::eof || error == boost::asio::error::connection_reset) break;
  }
  EXPECT_GE(server_->stats().connections_refused, 1U);
  held.clear();
  // Room again once the server saw them close (bounded retries).
  int status = 0;
  for (int attempt = 0; attempt < 100 && status != 404; ++attempt) {
    status = request(http::verb::get, "/").result_int();
  }
  EXPECT_EQ(status, 404);
}

TEST_F(LinkServerSecurityTest, AKeptAliveConnectionEndsAfterItsTotalTime) {
  ServerOptions options;
  options.http_connection_max_s = 0.2;
  start(options);
  boost::asio::io_context io;
  boost::beast::tcp_stream stream(io);
  stream.connect(testing::loopback(server_->port()));
  bool closed = false;
  const auto deadline = std::chrono::steady_clock::now() + testing::kWait;
  while (!closed && std::chrono::steady_clock::now() < deadline) {
    http::request<http::empty_body> get{http::verb::get, "/", 11};
    get.set(http::field::host, "127.0.0.1");
    get.keep_alive(true);
    boost::beast::error_code error;
    stream.expires_after(testing::kWait);
    http::write(stream, get, error);
    boost::beast::flat_buffer buffer;
    http::response<http::string_body> response;
    if (!error) http::read(stream, buffer, response, error);
    closed = static_cast<bool>(error);
  }
  EXPECT_TRUE(closed) << "the server kept the connection past its total time";
}

}  // namespace
}  // namespace marsokhod::link
