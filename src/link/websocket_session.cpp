#include "link/websocket_session.hpp"

#include <chrono>

#include <boost/asio/buffer.hpp>
#include <boost/beast/core/buffers_to_string.hpp>
#include <boost/beast/websocket.hpp>

#include "link/operator_message.hpp"

namespace marsokhod::link {
namespace {

namespace beast = boost::beast;
namespace websocket = beast::websocket;

constexpr auto kHandshakeTimeout = std::chrono::seconds(10);
// Larger than any legal message, so that the parser, not the transport, rejects an oversized
// one — with an error naming the limit instead of a closed connection.
constexpr std::size_t kReadMessageMaxBytes = 16 * kMaxOperatorMessageBytes;

}  // namespace

WebSocketSession::WebSocketSession(boost::asio::ip::tcp::socket&& socket, ServerCore& core)
    : ws_(std::move(socket)), core_(core) {}

WebSocketSession::~WebSocketSession() { core_.untrack(key_); }

void WebSocketSession::run(beast::http::request<beast::http::string_body> request) {
  key_ = core_.track(weak_from_this());
  // From here on the WebSocket's own timeouts apply, not the HTTP request's.
  beast::get_lowest_layer(ws_).expires_never();
  websocket::stream_base::timeout timeouts{};
  timeouts.handshake_timeout = kHandshakeTimeout;
  timeouts.idle_timeout = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(core_.options().idle_timeout_s));
  // Pings keep a quiet but live console connected and find a dead one within the timeout.
  timeouts.keep_alive_pings = true;
  ws_.set_option(timeouts);
  ws_.set_option(websocket::stream_base::decorator([](websocket::response_type& response) {
    response.set(beast::http::field::server, "marsokhod-link");
    response.set("X-Content-Type-Options", "nosniff");
    response.set("Referrer-Policy", "no-referrer");
  }));
  ws_.read_message_max(kReadMessageMaxBytes);
  ws_.async_accept(request, [self = shared_from_this()](beast::error_code error) {
    self->on_accept(error);
  });
}

void WebSocketSession::on_accept(beast::error_code error) {
  if (error || core_.stopping()) {
    close();
    return;
  }
  try {
    client_ = core_.add_client(shared_from_this());
  } catch (const std::exception& failure) {
    core_.on_handler_failure("a console's hello", failure);
    finish();
    return;
  }
  read();
}

void WebSocketSession::read() {
  ws_.async_read(buffer_, [self = shared_from_this()](beast::error_code error, std::size_t) {
    self->on_read(error);
  });
}

void WebSocketSession::on_read(beast::error_code error) {
  if (error) {
    finish();
    return;
  }
  try {
    if (ws_.got_text()) {
      core_.on_text(client_, beast::buffers_to_string(buffer_.data()));
    } else {
      core_.on_binary(client_);
    }
  } catch (const std::exception& failure) {
    // Never a dead session holding control: this one ends, and if it held control, its end is a
    // disconnect, which stops the rover.
    core_.on_handler_failure("a console's message", failure);
    finish();
    return;
  }
  buffer_.consume(buffer_.size());
  read();
}

void WebSocketSession::send(std::shared_ptr<const std::string> text) {
  if (closed_) return;
  if (queue_.size() >= core_.options().client_queue_messages) {
    core_.on_slow_client(client_);
    close();
    return;
  }
  queue_.push_back(std::move(text));
  if (!writing_) write_next();
}

void WebSocketSession::write_next() {
  writing_ = true;
  ws_.text(true);
  // The queue keeps the text alive until the write completes (front is popped in on_write).
  ws_.async_write(boost::asio::buffer(*queue_.front()),
                  [self = shared_from_this()](beast::error_code error, std::size_t) {
                    self->on_write(error);
                  });
}

void WebSocketSession::on_write(beast::error_code error) {
  if (error) {
    close();
    return;
  }
  queue_.pop_front();
  if (queue_.empty() || closed_) {
    writing_ = false;
  } else {
    write_next();
  }
}

void WebSocketSession::close() {
  if (closed_) return;
  closed_ = true;
  beast::get_lowest_layer(ws_).close();
}

void WebSocketSession::finish() {
  close();
  if (client_ == 0 || finished_) return;
  finished_ = true;
  core_.remove_client(client_);
}

}  // namespace marsokhod::link
