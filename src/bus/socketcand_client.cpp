#include "bus/socketcand_client.hpp"

#include <algorithm>
#include <array>
#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/write.hpp>
#include <optional>
#include <variant>

#include "bus/socketcand_protocol.hpp"

namespace marsokhod::bus {
namespace {

namespace asio = boost::asio;
using tcp = asio::ip::tcp;
using Clock = std::chrono::steady_clock;

std::string millis(std::chrono::milliseconds duration) {
  return std::to_string(duration.count()) + " ms";
}

// What a message is, for "expected X, got Y" errors: the raw text, or the framing problem.
std::string describe(const socketcand::MessageSplitter::Item& item) {
  // The server's words, escaped: a hostile one must not put control sequences on our terminal.
  if (const auto* text = std::get_if<std::string>(&item)) return "'" + socketcand::escaped(*text) + "'";
  return "unparseable data (" + socketcand::escaped(std::get<socketcand::ParseError>(item).reason) + ")";
}

}  // namespace

struct SocketcandClient::Impl {
  Config config;
  std::string endpoint;  // "HOST:PORT" for messages, IPv6 in brackets
  asio::io_context io;
  tcp::socket socket{io};
  socketcand::MessageSplitter splitter;
  std::array<char, 4096> read_buffer{};
  TransportCounters counters;
  std::string last_peer_error;
  std::optional<std::string> broken;  // why the connection is unusable; every call then throws

  explicit Impl(Config c) : config(std::move(c)) {
    const bool ipv6 = config.host.find(':') != std::string::npos;
    endpoint = (ipv6 ? "[" + config.host + "]" : config.host) + ":" + std::to_string(config.port);
  }

  // Runs the one pending asynchronous operation until it completes or `timeout` passes, then
  // cancels it and lets its handler run, so no operation outlives the call. A timed-out operation
  // ends with operation_aborted; one that completed just as time ran out keeps its own result.
  void run_for(Clock::duration timeout) {
    io.restart();
    io.run_for(timeout);
    if (io.stopped()) return;
    boost::system::error_code ignored;
    socket.cancel(ignored);
    io.restart();
    io.run();
  }

  [[noreturn]] void fail(const std::string& message) {
    broken = message;
    boost::system::error_code ignored;
    socket.close(ignored);
    throw TransportError(message);
  }

  std::vector<tcp::endpoint> resolve() {
    boost::system::error_code error;
    const auto address = asio::ip::make_address(config.host, error);
    if (!error) return {tcp::endpoint(address, config.port)};
    // A name: the system resolver bounds this with its own timeouts (resolv.conf).
    tcp::resolver resolver(io);
    const auto results = resolver.resolve(config.host, std::to_string(config.port), error);
    if (error || results.empty()) {
      throw TransportError("cannot resolve socketcand host '" + config.host +
                           "': " + error.message() + ": check the name in the transport URL");
    }
    std::vector<tcp::endpoint> endpoints;
    for (const auto& entry : results) endpoints.push_back(entry.endpoint());
    return endpoints;
  }

  void connect() {
    const auto endpoints = resolve();
    boost::system::error_code result = asio::error::would_block;
    asio::async_connect(
        socket, endpoints,
        [&](const boost::system::error_code& error, const tcp::endpoint&) { result = error; });
    run_for(config.connect_timeout);
    if (result == asio::error::operation_aborted) {
      fail("timed out after " + millis(config.connect_timeout) + " connecting to socketcand at " +
           endpoint + ": is the host reachable and the port open?");
    }
    if (result) {
      fail("cannot connect to socketcand at " + endpoint + ": " + result.message() +
           ": is `marsokhod sim` (or socketcand) running and listening on that port?");
    }
    socket.set_option(tcp::no_delay(true), result);  // small messages; latency matters
  }

  // Reads once, waiting at most `timeout`; returns false when nothing arrived in time.
  bool read_some(Clock::duration timeout) {
    boost::system::error_code result = asio::error::would_block;
    std::size_t size = 0;
    socket.async_read_some(asio::buffer(read_buffer),
                           [&](const boost::system::error_code& error, std::size_t n) {
                             result = error;
                             size = n;
                           });
    run_for(timeout);
    if (result == asio::error::operation_aborted) return false;
    if (result == asio::error::eof) fail("socketcand at " + endpoint + " closed the connection");
    if (result) fail("connection to socketcand at " + endpoint + " lost: " + result.message());
    splitter.append(std::string_view(read_buffer.data(), size));
    return true;
  }

  void write(const std::string& text) {
    if (broken) throw TransportError(*broken);
    boost::system::error_code result = asio::error::would_block;
    asio::async_write(socket, asio::buffer(text),
                      [&](const boost::system::error_code& error, std::size_t) { result = error; });
    run_for(config.send_timeout);
    if (result == asio::error::operation_aborted) {
      fail("timed out after " + millis(config.send_timeout) + " sending to socketcand at " +
           endpoint + ": the server stopped reading");
    }
    if (result) fail("connection to socketcand at " + endpoint + " lost: " + result.message());
  }

  // The next message of the handshake, waiting at most the handshake timeout for it.
  socketcand::MessageSplitter::Item next_handshake_item(const char* expected) {
    const auto deadline = Clock::now() + config.handshake_timeout;
    while (true) {
      if (auto item = splitter.next()) return *item;
      const auto now = Clock::now();
      if (now >= deadline || !read_some(deadline - now)) {
        fail("socketcand at " + endpoint + " did not send " + expected + " within " +
             millis(config.handshake_timeout) + ": is it a socketcand server?");
      }
    }
  }

  template <class Expected>
  void expect(const char* expected, const char* step) {
    const auto item = next_handshake_item(expected);
    if (const auto* text = std::get_if<std::string>(&item)) {
      const auto parsed = socketcand::parse_message(*text);
      if (const auto* message = std::get_if<socketcand::Message>(&parsed)) {
        if (std::holds_alternative<Expected>(*message)) return;
        if (const auto* error = std::get_if<socketcand::Error>(message)) {
          fail("socketcand at " + endpoint + " refused " + step + ": " +
               socketcand::escaped(error->text));
        }
      }
    }
    fail("socketcand at " + endpoint + " answered " + step + " with " + describe(item) +
         " instead of " + expected + ": is it a socketcand server?");
  }

  void handshake() {
    expect<socketcand::Hi>("the greeting '< hi >'", "the connection");
    write(socketcand::format_message(socketcand::Open{config.channel}));
    expect<socketcand::Ok>("'< ok >'", ("opening channel '" + config.channel + "'").c_str());
    write(socketcand::format_message(socketcand::RawMode{}));
    expect<socketcand::Ok>("'< ok >'", "raw mode");
  }

  void take(const socketcand::MessageSplitter::Item& item, std::vector<protocol::CanFrame>& out);
};

void SocketcandClient::Impl::take(const socketcand::MessageSplitter::Item& item,
                                  std::vector<protocol::CanFrame>& out) {
  const auto* text = std::get_if<std::string>(&item);
  if (text == nullptr) {
    ++counters.malformed_dropped;
    return;
  }
  const auto parsed = socketcand::parse_message(*text);
  const auto* message = std::get_if<socketcand::Message>(&parsed);
  if (message == nullptr) {
    ++counters.malformed_dropped;
  } else if (const auto* frame = std::get_if<socketcand::Frame>(message)) {
    if (frame->extended) {
      ++counters.ignored;
      return;
    }
    out.push_back(frame->frame);
    ++counters.frames_received;
  } else if (const auto* error = std::get_if<socketcand::Error>(message)) {
    ++counters.peer_errors;
    last_peer_error = socketcand::escaped(error->text);
  } else if (!std::holds_alternative<socketcand::Echo>(*message)) {
    ++counters.ignored;  // fdframe, rtr, stat, …: valid socketcand, not classic data frames
  }
}

SocketcandClient::SocketcandClient(Config config)
    : impl_(std::make_unique<Impl>(std::move(config))) {
  if (!socketcand::valid_channel_name(impl_->config.channel)) {
    throw TransportError("socketcand channel '" + impl_->config.channel +
                         "' is not a bus name (1-16 characters, no spaces, '/', ':', '<', '>')");
  }
  impl_->connect();
  impl_->handshake();
}

SocketcandClient::~SocketcandClient() = default;

void SocketcandClient::send(const protocol::CanFrame& frame) {
  if (frame.id > 0x7FF || frame.dlc > 8) {
    throw TransportError("cannot send to " + name() + ": " + describe_frame(frame) +
                         " is not a classic frame (11-bit identifier, at most 8 bytes)");
  }
  impl_->write(socketcand::format_message(socketcand::Send{frame, false}));
  ++impl_->counters.frames_sent;
}

std::vector<protocol::CanFrame> SocketcandClient::receive(std::chrono::microseconds timeout) {
  if (impl_->broken) throw TransportError(*impl_->broken);
  std::vector<protocol::CanFrame> frames;
  // Clamped so that a caller's "wait forever" cannot overflow the deadline.
  const auto deadline =
      Clock::now() + std::min(timeout, std::chrono::microseconds(std::chrono::hours(24)));
  while (true) {
    while (auto item = impl_->splitter.next()) impl_->take(*item, frames);
    const auto now = Clock::now();
    if (!frames.empty() || now >= deadline || !impl_->read_some(deadline - now)) return frames;
  }
}

std::string SocketcandClient::name() const {
  return "socketcand://" + impl_->endpoint + "/" + impl_->config.channel;
}

TransportCounters SocketcandClient::counters() const { return impl_->counters; }

std::string SocketcandClient::last_peer_error() const { return impl_->last_peer_error; }

}  // namespace marsokhod::bus
