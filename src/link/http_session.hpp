// One HTTP connection: the console's files (GET, HEAD), and the WebSocket upgrade at /ws, which
// is checked here (path, token, room) and then handed to a WebSocketSession. Internal.
#pragma once

#include <memory>
#include <optional>

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
  void upgrade(Request&& request);
  void respond(const Request& request);
  void send_file(const Request& request, const std::filesystem::path& file);
  void send_text(const Request& request, boost::beast::http::status status, std::string body);
  template <typename Body>
  void send(boost::beast::http::response<Body>&& response);

  boost::beast::tcp_stream stream_;
  ServerCore& core_;
  boost::beast::flat_buffer buffer_;
  std::optional<boost::beast::http::request_parser<boost::beast::http::string_body>> parser_;
  std::uint64_t key_ = 0;
};

}  // namespace marsokhod::link
