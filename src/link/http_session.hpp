// One HTTP connection: the console's files (GET, HEAD), POST /session (the token for a session
// cookie), and the WebSocket upgrade at /ws, which is checked here (Host, path, Origin, cookie or
// token, room) and then handed to a WebSocketSession. Every response carries nosniff,
// no-referrer and a Content-Security-Policy that forbids framing. A connection lives at most
// ServerOptions::http_connection_max_s in all, however many requests it keeps alive. Internal.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http.hpp>

#include "link/server_core.hpp"

namespace marsokhod::link {

class HttpSession : public Connection, public std::enable_shared_from_this<HttpSession> {
 public:
  using Request = boost::beast::http::request<boost::beast::http::string_body>;

  HttpSession(boost::asio::ip::tcp::socket&& socket, ServerCore& core);
  ~HttpSession() override;
  HttpSession(const HttpSession&) = delete;
  HttpSession& operator=(const HttpSession&) = delete;

  void run();
  void close() override;

 private:
  void read();
  void on_read(boost::beast::error_code error);
  void handle(Request&& request);
  void upgrade(Request&& request);
  void open_session(const Request& request);
  // 401 or 429 for a refused token; false when it was allowed.
  bool refuse_token(const Request& request, const AuthDecision& decision);
  void respond(const Request& request);
  void send_file(const Request& request, const std::filesystem::path& file);
  void send_text(const Request& request, boost::beast::http::status status, std::string body);
  template <typename Body>
  void send(const Request& request, boost::beast::http::response<Body>&& response);

  boost::beast::tcp_stream stream_;
  ServerCore& core_;
  boost::beast::flat_buffer buffer_;
  std::optional<boost::beast::http::request_parser<boost::beast::http::string_body>> parser_;
  std::uint64_t key_ = 0;
  std::string address_;  // the client's IP, for the wrong-token back-off and the log
  std::chrono::steady_clock::time_point deadline_;  // the connection's end, keep-alive or not
};

}  // namespace marsokhod::link
