// A console for the tests: a Beast WebSocket client and a one-shot HTTP client on loopback, each
// with its own io_context run only inside a call, and every wait bounded by a deadline (a hung
// server fails the test instead of hanging it).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

namespace marsokhod::link::testing {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using namespace std::chrono_literals;

inline constexpr std::chrono::milliseconds kWait = 5s;

// Runs `io` until `done` or the deadline; true if done.
inline bool run_until(asio::io_context& io, const bool& done, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  io.restart();
  while (!done && std::chrono::steady_clock::now() < deadline) io.run_one_until(deadline);
  return done;
}

using Headers = std::vector<std::pair<std::string, std::string>>;

inline asio::ip::tcp::endpoint loopback(std::uint16_t port) {
  return {asio::ip::make_address("127.0.0.1"), port};
}

class TestClient {
 public:
  // Connects and asks for the upgrade at `target` with `headers` (Authorization, Cookie,
  // Origin, Host); open() tells whether the server accepted.
  TestClient(std::uint16_t port, const std::string& target, const Headers& headers = {})
      : ws_(io_) {
    ws_.set_option(websocket::stream_base::decorator([headers](websocket::request_type& request) {
      for (const auto& [name, value] : headers) request.set(name, value);
    }));
    bool done = false;
    beast::get_lowest_layer(ws_).async_connect(loopback(port), [&](beast::error_code error) {
      error_ = error;
      if (error) {
        done = true;
        return;
      }
      ws_.async_handshake(response_, "127.0.0.1", target, [&](beast::error_code e) {
        error_ = e;
        done = true;
      });
    });
    if (!run_until(io_, done, kWait)) error_ = asio::error::timed_out;
    open_ = !error_;
  }

  bool open() const { return open_; }
  const beast::error_code& error() const { return error_; }
  const websocket::response_type& handshake_response() const { return response_; }

  bool send(const std::string& text, bool binary = false) {
    bool done = false;
    ws_.binary(binary);
    ws_.async_write(asio::buffer(text), [&](beast::error_code error, std::size_t) {
      error_ = error;
      done = true;
    });
    return run_until(io_, done, kWait) && !error_;
  }
  bool send(const nlohmann::json& message) { return send(message.dump()); }

  // One message as it came: text or binary.
  struct Frame {
    bool binary = false;
    std::string data;
  };

  // The next message, or nullopt after `timeout` or when the connection ended (then closed()).
  std::optional<Frame> receive_frame(std::chrono::milliseconds timeout = kWait) {
    if (!read_pending_) {
      read_pending_ = true;
      read_done_ = false;
      ws_.async_read(buffer_, [this](beast::error_code error, std::size_t) {
        read_error_ = error;
        read_done_ = true;
      });
    }
    if (!run_until(io_, read_done_, timeout)) return std::nullopt;
    read_pending_ = false;
    if (read_error_) {
      closed_ = true;
      return std::nullopt;
    }
    Frame frame{ws_.got_binary(), beast::buffers_to_string(buffer_.data())};
    buffer_.consume(buffer_.size());
    return frame;
  }

  // The next message as JSON (a text message).
  std::optional<nlohmann::json> receive(std::chrono::milliseconds timeout = kWait) {
    const auto frame = receive_frame(timeout);
    if (!frame) return std::nullopt;
    return nlohmann::json::parse(frame->data);
  }

  // The next message of `type`, skipping others (a status may come at any time).
  std::optional<nlohmann::json> receive_type(const std::string& type,
                                             std::chrono::milliseconds timeout = kWait) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          deadline - std::chrono::steady_clock::now());
      if (left <= 0ms) return std::nullopt;
      auto message = receive(left);
      if (!message || (*message)["type"] == type) return message;
    }
  }

  // True once the server ended the connection (reads until then, at most `timeout`).
  bool wait_closed(std::chrono::milliseconds timeout = kWait) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (!closed_ && std::chrono::steady_clock::now() < deadline) {
      receive(std::chrono::duration_cast<std::chrono::milliseconds>(
          deadline - std::chrono::steady_clock::now()));
    }
    return closed_;
  }

  // Drops the connection without a closing handshake, as a crashed browser would.
  void drop() { beast::get_lowest_layer(ws_).close(); }

 private:
  asio::io_context io_;
  websocket::stream<beast::tcp_stream> ws_;
  beast::flat_buffer buffer_;
  websocket::response_type response_;
  beast::error_code error_;
  beast::error_code read_error_;
  bool open_ = false;
  bool read_pending_ = false;
  bool read_done_ = false;
  bool closed_ = false;
};

// One HTTP request on a fresh connection; the response, or a 599 one if none came in time.
inline http::response<http::string_body> http_request(std::uint16_t port, http::verb method,
                                                      const std::string& target,
                                                      const Headers& headers = {}) {
  asio::io_context io;
  beast::tcp_stream stream(io);
  http::request<http::empty_body> request{method, target, 11};
  request.set(http::field::host, "127.0.0.1");
  for (const auto& [name, value] : headers) request.set(name, value);
  http::response<http::string_body> response;
  http::response_parser<http::string_body> parser;
  parser.skip(method == http::verb::head);  // a HEAD response has a length but no body
  beast::flat_buffer buffer;
  bool done = false;
  stream.async_connect(loopback(port), [&](beast::error_code error) {
    if (error) {
      done = true;
      return;
    }
    http::async_write(stream, request, [&](beast::error_code e, std::size_t) {
      if (e) {
        done = true;
        return;
      }
      http::async_read(stream, buffer, parser, [&](beast::error_code, std::size_t) {
        done = true;
      });
    });
  });
  if (!run_until(io, done, kWait) || !parser.is_header_done()) {
    response.result(599);
    return response;
  }
  return parser.release();
}

}  // namespace marsokhod::link::testing
