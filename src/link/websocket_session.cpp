#include "link/websocket_session.hpp"

#include <algorithm>
#include <chrono>

#include <boost/asio/buffer.hpp>
#include <boost/beast/core/buffers_to_string.hpp>
#include <boost/beast/websocket.hpp>

#include "link/foxglove_protocol.hpp"
#include "link/operator_message.hpp"

namespace marsokhod::link {
namespace {

namespace beast = boost::beast;
namespace websocket = beast::websocket;

constexpr auto kHandshakeTimeout = std::chrono::seconds(10);
// Larger than any legal message, so that the parser, not the transport, rejects an oversized
// one — with an error naming the limit instead of a closed connection.
constexpr std::size_t kReadMessageMaxBytes =
    std::max(16 * kMaxOperatorMessageBytes, 2 * foxglove::kMaxClientMessageBytes);

}  // namespace

WebSocketSession::WebSocketSession(boost::asio::ip::tcp::socket&& socket, ServerCore& core,
                                   Kind kind)
    : ws_(std::move(socket)), core_(core), kind_(kind) {}

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
  const bool foxglove = kind_ == Kind::kFoxglove;
  ws_.set_option(websocket::stream_base::decorator([foxglove](websocket::response_type& response) {
    // The subprotocol the client offered (the upgrade was refused without it).
    if (foxglove) {
      response.set(beast::http::field::sec_websocket_protocol,
                   std::string(foxglove::kSubprotocol));
    }
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
    client_ = kind_ == Kind::kFoxglove ? core_.add_foxglove_client(shared_from_this())
                                       : core_.add_client(shared_from_this());
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
    if (kind_ == Kind::kFoxglove) {
      if (ws_.got_text()) {
        core_.on_foxglove_text(client_, beast::buffers_to_string(buffer_.data()));
      } else {
        core_.on_foxglove_binary(client_);
      }
    } else if (ws_.got_text()) {
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
  push({std::move(text), false, false});
}

void WebSocketSession::send_foxglove(std::shared_ptr<const std::string> data, bool binary,
                                     bool droppable) {
  if (closed_) return;
  const std::size_t limit = core_.options().foxglove_queue_messages;
  if (queue_.size() >= limit) {
    // The oldest droppable message not being written gives way; else this one, if it may.
    const auto first = queue_.begin() + (writing_ ? 1 : 0);
    const auto oldest = std::find_if(first, queue_.end(),
                                     [](const Outgoing& m) { return m.droppable; });
    if (oldest != queue_.end()) {
      queue_.erase(oldest);
      core_.on_foxglove_dropped(1);
    } else if (droppable) {
      core_.on_foxglove_dropped(1);
      return;
    } else if (queue_.size() >= 2 * limit) {
      core_.on_slow_client(client_);
      close();
      return;
    }
  }
  push({std::move(data), binary, droppable});
}

void WebSocketSession::push(Outgoing message) {
  queue_.push_back(std::move(message));
  if (!writing_) write_next();
}

void WebSocketSession::write_next() {
  writing_ = true;
  ws_.binary(queue_.front().binary);
  // The queue keeps the text alive until the write completes (front is popped in on_write).
  ws_.async_write(boost::asio::buffer(*queue_.front().data),
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
  if (kind_ == Kind::kFoxglove) {
    core_.remove_foxglove_client(client_);
  } else {
    core_.remove_client(client_);
  }
}

}  // namespace marsokhod::link
