// The console's files over plain HTTP: index.html at "/", MIME types, no way out of the root,
// 404 for the rest — all without the token (the files carry no data).
#include "link/link_server.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "test_client.hpp"

namespace marsokhod::link {
namespace {

namespace fs = std::filesystem;
namespace http = testing::http;

class LinkServerHttpTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("marsokhod_link_http_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "dist" / "assets");
    std::ofstream(root_ / "dist" / "index.html") << "<!doctype html><title>console</title>";
    std::ofstream(root_ / "dist" / "assets" / "app.js") << "console.log('rover');";
    std::ofstream(root_ / "secret.txt") << "not for the browser";
    ServerOptions options;
    options.listen = {"127.0.0.1", 0};
    options.static_dir = root_ / "dist";
    server_ = std::make_unique<LinkServer>(Params{}, options);
    server_->start();
  }
  void TearDown() override {
    server_.reset();
    fs::remove_all(root_);
  }
  http::response<http::string_body> get(const std::string& target,
                                        http::verb method = http::verb::get) {
    return testing::http_request(server_->port(), method, target);
  }

  fs::path root_;
  std::unique_ptr<LinkServer> server_;
};

TEST_F(LinkServerHttpTest, ServesIndexHtmlAtTheRoot) {
  const auto response = get("/");
  EXPECT_EQ(response.result_int(), 200);
  EXPECT_EQ(response[http::field::content_type], "text/html; charset=utf-8");
  EXPECT_EQ(response.body(), "<!doctype html><title>console</title>");
  EXPECT_EQ(get("/index.html").body(), response.body());
  EXPECT_EQ(get("/?token=anything").result_int(), 200);  // the page loads without the token
}

TEST_F(LinkServerHttpTest, ServesAssetsWithTheirMimeType) {
  const auto response = get("/assets/app.js");
  EXPECT_EQ(response.result_int(), 200);
  EXPECT_EQ(response[http::field::content_type], "text/javascript; charset=utf-8");
  EXPECT_EQ(response.body(), "console.log('rover');");
}

TEST_F(LinkServerHttpTest, AnswersHeadWithTheLengthOnly) {
  const auto response = get("/assets/app.js", http::verb::head);
  EXPECT_EQ(response.result_int(), 200);
  EXPECT_EQ(response[http::field::content_length], "21");
  EXPECT_TRUE(response.body().empty());
}

TEST_F(LinkServerHttpTest, RejectsDotDot) {
  for (const char* target : {"/../secret.txt", "/assets/../../secret.txt", "/%2e%2e/secret.txt"}) {
    const auto response = get(target);
    EXPECT_EQ(response.result_int(), 400) << target;
    EXPECT_EQ(response.body().find("not for the browser"), std::string::npos) << target;
  }
}

TEST_F(LinkServerHttpTest, AnswersMissingFilesWith404) {
  EXPECT_EQ(get("/missing.html").result_int(), 404);
  EXPECT_EQ(get("/assets").result_int(), 404);  // a directory without index.html
  EXPECT_EQ(get("/assets/").result_int(), 404);
}

TEST_F(LinkServerHttpTest, AllowsOnlyGetAndHead) {
  const auto response = get("/", http::verb::post);
  EXPECT_EQ(response.result_int(), 405);
  EXPECT_EQ(response[http::field::allow], "GET, HEAD");
}

TEST_F(LinkServerHttpTest, AUpgradeElsewhereThanWsIs404) {
  testing::TestClient client(server_->port(), "/socket",
                             {{"Authorization", "Bearer " + server_->token()}});
  EXPECT_FALSE(client.open());
  EXPECT_EQ(client.handshake_response().result_int(), 404);
}

}  // namespace
}  // namespace marsokhod::link
