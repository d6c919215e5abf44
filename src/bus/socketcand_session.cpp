#include "bus/socketcand_session.hpp"

#include <boost/asio/write.hpp>
#include <cstdio>
#include <exception>
#include <variant>

namespace marsokhod::bus {
namespace {

namespace asio = boost::asio;
using socketcand::Message;

// The command word of a message, for "unexpected X" errors.
std::string verb_of(const Message& message) {
  static constexpr const char* kVerbs[] = {"hi",   "ok",    "echo", "rawmode",
                                           "open", "error", "send", "frame"};
  if (const auto* unsupported = std::get_if<socketcand::Unsupported>(&message))
    return unsupported->verb;
  return kVerbs[message.index()];
}

std::string millis(std::chrono::milliseconds duration) {
  return std::to_string(duration.count()) + " ms";
}

}  // namespace

SocketcandSession::SocketcandSession(SessionHost& host, asio::ip::tcp::socket socket)
    : host_(host),
      socket_(std::move(socket)),
      timer_(socket_.get_executor()),
      idle_timer_(socket_.get_executor()) {}

void SocketcandSession::start() {
  deliver(socketcand::format_message(socketcand::Hi{}), false);
  const auto timeout = host_.config().handshake_timeout;
  timer_.expires_after(timeout);
  timer_.async_wait([self = shared_from_this(), timeout](const boost::system::error_code& error) {
    if (error || self->closed_ || self->state_ != State::kNoBus) return;
    self->host_.count(&ServerCounters::clients_refused);
    self->refuse("no 'open " + self->host_.config().channel + "' within " + millis(timeout));
  });
  read();
}

void SocketcandSession::read() {
  socket_.async_read_some(
      asio::buffer(read_buffer_),
      [self = shared_from_this()](const boost::system::error_code& error, std::size_t size) {
        if (self->closed_) return;
        if (error) {
          self->close();  // the client left (or the connection broke): nothing to answer
          return;
        }
        try {
          self->on_read(size);
        } catch (const std::exception& failure) {
          // This client's handler failed: it ends, the server and the other clients go on.
          std::fprintf(stderr, "socketcand server: closing a client: %s\n", failure.what());
          self->close();
        }
      });
}

void SocketcandSession::on_read(std::size_t size) {
  touch();
  splitter_.append(std::string_view(read_buffer_.data(), size));
  while (state_ != State::kClosing && !closed_) {
    const auto item = splitter_.next();
    if (!item) break;
    if (const auto* text = std::get_if<std::string>(&*item)) {
      handle(*text);
      continue;
    }
    const auto& error = std::get<socketcand::ParseError>(*item);
    if (error.http_request || (error.outside_message && state_ == State::kNoBus)) {
      // A web page's request (or something else that is not socketcand): nothing after it may
      // reach the bus.
      host_.count(&ServerCounters::clients_refused);
      refuse(error.http_request ? "an HTTP request is not socketcand; closing"
                                : error.reason + " before 'open': closing");
    } else {
      reject(error.reason);
    }
  }
  if (state_ != State::kClosing && !closed_) read();
}

void SocketcandSession::handle(const std::string& text) {
  const auto parsed = socketcand::parse_message(text);
  if (const auto* error = std::get_if<socketcand::ParseError>(&parsed)) {
    reject(error->reason);
    return;
  }
  const auto& message = std::get<Message>(parsed);
  // Anything the client sends after raw mode proves its handshake reads are done (see
  // Config::rawmode_grace).
  if (state_ == State::kRaw) start_streaming();
  if (std::holds_alternative<socketcand::Echo>(message)) {
    deliver(text, false);
  } else if (std::holds_alternative<socketcand::Error>(message)) {
    // A client's error report needs no answer; answering errors with errors could ping-pong.
  } else if (state_ == State::kNoBus) {
    handle_no_bus(message);
  } else {
    handle_bus(message);
  }
}

void SocketcandSession::handle_no_bus(const Message& message) {
  const auto* open = std::get_if<socketcand::Open>(&message);
  if (open == nullptr) {
    reject("'" + verb_of(message) + "' before the bus is open: send 'open " +
           host_.config().channel + "' first");
  } else if (open->channel != host_.config().channel) {
    host_.count(&ServerCounters::clients_refused);
    refuse("could not open bus '" + open->channel + "': this server has only '" +
           host_.config().channel + "'");
  } else {
    timer_.cancel();
    state_ = State::kBus;
    touch();
    deliver(socketcand::format_message(socketcand::Ok{}), false);
  }
}

void SocketcandSession::handle_bus(const Message& message) {
  if (const auto* send = std::get_if<socketcand::Send>(&message)) {
    handle_send(*send);
  } else if (std::holds_alternative<socketcand::RawMode>(message)) {
    enter_raw_mode();
  } else if (std::holds_alternative<socketcand::Unsupported>(message)) {
    reject("unknown command '" + verb_of(message) +
           "': this server speaks raw mode only (open, rawmode, send, echo)");
  } else {
    reject("unexpected '" + verb_of(message) + "' from a client after the bus was opened");
  }
}

void SocketcandSession::handle_send(const socketcand::Send& send) {
  if (send.extended) {
    reject(
        "send: extended (29-bit) identifiers are not supported; the rover's bus uses 11-bit ones");
    return;
  }
  try {
    host_.frame_from_client(*this, send.frame);
  } catch (const std::exception& e) {
    reject(std::string("send: frame rejected by the simulator: ") + e.what());
  }
}

void SocketcandSession::enter_raw_mode() {
  if (state_ == State::kRaw) {
    deliver(socketcand::format_message(socketcand::Ok{}), false);
    return;
  }
  state_ = State::kRaw;
  deliver(socketcand::format_message(socketcand::Ok{}), false);
  const auto grace = host_.config().rawmode_grace;
  if (grace <= std::chrono::milliseconds::zero()) {
    start_streaming();
    return;
  }
  timer_.expires_after(grace);
  timer_.async_wait([self = shared_from_this()](const boost::system::error_code& error) {
    if (!error) self->start_streaming();
  });
}

void SocketcandSession::start_streaming() {
  if (streaming_ || closed_) return;
  streaming_ = true;
  timer_.cancel();
  host_.streaming_started();
}

void SocketcandSession::reject(const std::string& reason) {
  host_.count(&ServerCounters::malformed_messages);
  deliver(socketcand::format_message(socketcand::Error{reason}), false);
}

void SocketcandSession::refuse(const std::string& reason) {
  deliver(socketcand::format_message(socketcand::Error{reason}), false);
  state_ = State::kClosing;
  if (!writing_) close();
}

void SocketcandSession::deliver(const std::string& text, bool droppable) {
  if (closed_ || (state_ == State::kClosing && droppable)) return;
  const std::size_t limit = host_.config().max_queued_bytes;
  if (queued_bytes_ + text.size() > limit) {
    if (droppable) {
      host_.count(&ServerCounters::frames_dropped);
      return;
    }
    close();  // it sends but never reads our replies: nothing else bounds its queue
    return;
  }
  queue_.push_back(text);
  queued_bytes_ += text.size();
  if (!writing_) write_next();
}

void SocketcandSession::write_next() {
  writing_ = true;
  asio::async_write(
      socket_, asio::buffer(queue_.front()),
      [self = shared_from_this()](const boost::system::error_code& error, std::size_t) {
        if (self->closed_) return;
        self->queued_bytes_ -= self->queue_.front().size();
        self->queue_.pop_front();
        if (error) {
          self->close();
        } else if (!self->queue_.empty()) {
          self->touch();
          self->write_next();
        } else {
          self->writing_ = false;
          self->touch();
          if (self->state_ == State::kClosing) self->close();
        }
      });
}

void SocketcandSession::touch() {
  if (closed_ || state_ == State::kNoBus || state_ == State::kClosing) return;
  last_activity_ = std::chrono::steady_clock::now();
  if (!idle_armed_) arm_idle_timer(last_activity_ + host_.config().idle_timeout);
}

// One wait at a time (touch() runs for every frame written); at its end the deadline is worked
// out again from the latest activity.
void SocketcandSession::arm_idle_timer(std::chrono::steady_clock::time_point deadline) {
  idle_armed_ = true;
  idle_timer_.expires_at(deadline);
  idle_timer_.async_wait([self = shared_from_this()](const boost::system::error_code& e) {
    self->idle_armed_ = false;
    if (e || self->closed_ || self->state_ == State::kClosing) return;
    const auto timeout = self->host_.config().idle_timeout;
    const auto due = self->last_activity_ + timeout;
    if (std::chrono::steady_clock::now() < due) {
      self->arm_idle_timer(due);
      return;
    }
    self->host_.count(&ServerCounters::clients_refused);
    self->refuse("idle for " + millis(timeout) + ": closing");
  });
}

void SocketcandSession::close() {
  if (closed_) return;
  closed_ = true;
  idle_timer_.cancel();
  boost::system::error_code ignored;
  socket_.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
  timer_.cancel();
  queue_.clear();
  queued_bytes_ = 0;
  const bool was_streaming = streaming_;
  streaming_ = false;
  host_.closed(*this, was_streaming);
}

}  // namespace marsokhod::bus
