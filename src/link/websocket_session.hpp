// One console (or Foxglove client) on the WebSocket: reads its messages one at a time and hands
// them to the core; writes the core's messages from a bounded queue, one write in flight (Beast
// allows no more). A full queue means the client reads slower than the rover talks: a console
// is dropped, so that it can neither grow the server's memory nor hold up the others; a Foxglove
// client loses its oldest queued data messages instead (a stream: the newest matter), and is
// dropped only when its queue holds twice the limit of messages that may not be dropped.
// Internal.
#pragma once

#include <deque>
#include <memory>
#include <string>

#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/string_body.hpp>
#include <boost/beast/websocket/stream.hpp>

#include "link/server_core.hpp"

namespace marsokhod::link {

class WebSocketSession : public Connection,
                         public std::enable_shared_from_this<WebSocketSession> {
 public:
  enum class Kind { kConsole, kFoxglove };
  WebSocketSession(boost::asio::ip::tcp::socket&& socket, ServerCore& core,
                   Kind kind = Kind::kConsole);
  ~WebSocketSession() override;
  WebSocketSession(const WebSocketSession&) = delete;
  WebSocketSession& operator=(const WebSocketSession&) = delete;

  // Completes the upgrade the HTTP session accepted.
  void run(boost::beast::http::request<boost::beast::http::string_body> request);
  // Queues one text message; drops the client when its queue is full.
  void send(std::shared_ptr<const std::string> text);
  // A Foxglove client's message: binary or text; `droppable` (message data, time) gives way
  // when the queue is full.
  void send_foxglove(std::shared_ptr<const std::string> data, bool binary, bool droppable);
  // Closes the socket at once: pending reads and writes end with an error, then finish().
  void close() override;

 private:
  void on_accept(boost::beast::error_code error);
  void read();
  void on_read(boost::beast::error_code error);
  void write_next();
  void on_write(boost::beast::error_code error);
  void finish();

  boost::beast::websocket::stream<boost::beast::tcp_stream> ws_;
  ServerCore& core_;
  struct Outgoing {
    std::shared_ptr<const std::string> data;
    bool binary = false;
    bool droppable = false;
  };
  void push(Outgoing message);

  Kind kind_;
  boost::beast::flat_buffer buffer_;
  std::deque<Outgoing> queue_;
  std::uint64_t key_ = 0;
  ClientId client_ = 0;  // 0 until the handshake completed
  bool writing_ = false;
  bool closed_ = false;
  bool finished_ = false;
};

}  // namespace marsokhod::link
