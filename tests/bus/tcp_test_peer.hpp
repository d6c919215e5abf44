// Hand-driven TCP peers for the socketcand tests: a raw client that sends exactly the bytes a test
// chooses, and a one-connection server that plays a script. Loopback only; every wait bounded.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <variant>

#include <gtest/gtest.h>

#include "bus/socketcand_protocol.hpp"

namespace marsokhod::bus::testing {

using std::chrono::milliseconds;

// Long enough for a loaded CI machine, short enough that a hang fails the test quickly.
inline constexpr milliseconds kPatience{5000};

inline sockaddr_in loopback(std::uint16_t port) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(port);
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  return address;
}

class TcpConnection {
 public:
  explicit TcpConnection(int fd) : fd_(fd) {}
  ~TcpConnection() {
    if (fd_ >= 0) ::close(fd_);
  }
  TcpConnection(TcpConnection&& other) noexcept
      : fd_(other.fd_), splitter_(std::move(other.splitter_)) {
    other.fd_ = -1;
  }
  TcpConnection(const TcpConnection&) = delete;
  TcpConnection& operator=(const TcpConnection&) = delete;
  TcpConnection& operator=(TcpConnection&&) = delete;

  // Connecting over loopback either succeeds or is refused at once: no timeout needed.
  static TcpConnection connect_loopback(std::uint16_t port) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    const sockaddr_in address = loopback(port);
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
      ::close(fd);
      throw std::runtime_error("test peer cannot connect to 127.0.0.1:" + std::to_string(port));
    }
    const int one = 1;
    ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    return TcpConnection(fd);
  }

  void send_text(std::string_view text) {
    ASSERT_EQ(::send(fd_, text.data(), text.size(), MSG_NOSIGNAL),
              static_cast<ssize_t>(text.size()));
  }

  // The next complete `< … >` message; nullopt on timeout or when the peer closed. Framing errors
  // come back as "!" + reason so a test sees them.
  std::optional<std::string> read_message(milliseconds timeout = kPatience) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (true) {
      if (auto item = splitter_.next()) {
        if (const auto* text = std::get_if<std::string>(&*item)) return *text;
        return "!" + std::get<socketcand::ParseError>(*item).reason;
      }
      if (!read_some(deadline)) return std::nullopt;
    }
  }

  // True once the peer closed the connection (data before the end is discarded).
  bool wait_closed(milliseconds timeout = kPatience) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (read_some(deadline)) {
    }
    return closed_;
  }

 private:
  bool read_some(std::chrono::steady_clock::time_point deadline) {
    const auto left =
        std::chrono::duration_cast<milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd readable{fd_, POLLIN, 0};
    if (closed_ || left.count() <= 0 || ::poll(&readable, 1, static_cast<int>(left.count())) <= 0)
      return false;
    char buffer[4096];
    const ssize_t size = ::recv(fd_, buffer, sizeof buffer, 0);
    if (size <= 0) {
      closed_ = true;
      return false;
    }
    splitter_.append(std::string_view(buffer, static_cast<std::size_t>(size)));
    return true;
  }

  int fd_;
  socketcand::MessageSplitter splitter_;
  bool closed_ = false;
};

// Accepts one connection on an ephemeral loopback port and runs `script` with it on its own
// thread. The destructor joins: scripts must bound their waits.
class ScriptedServer {
 public:
  explicit ScriptedServer(std::function<void(TcpConnection&)> script) {
    listen_fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in address = loopback(0);
    socklen_t size = sizeof address;
    if (::bind(listen_fd_, reinterpret_cast<sockaddr*>(&address), size) != 0 ||
        ::listen(listen_fd_, 4) != 0 ||
        ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&address), &size) != 0) {
      throw std::runtime_error("test server cannot listen on 127.0.0.1");
    }
    port_ = ntohs(address.sin_port);
    thread_ = std::thread([this, script = std::move(script)] {
      pollfd pending{listen_fd_, POLLIN, 0};
      if (::poll(&pending, 1, static_cast<int>(kPatience.count())) <= 0) return;
      const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
      if (fd < 0) return;
      TcpConnection connection(fd);
      script(connection);
    });
  }
  ~ScriptedServer() {
    thread_.join();
    ::close(listen_fd_);
  }
  ScriptedServer(const ScriptedServer&) = delete;
  ScriptedServer& operator=(const ScriptedServer&) = delete;

  std::uint16_t port() const { return port_; }

 private:
  int listen_fd_ = -1;
  std::uint16_t port_ = 0;
  std::thread thread_;
};

// A loopback port nobody listens on: bound to find a free one, then released.
inline std::uint16_t unused_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in address = loopback(0);
  socklen_t size = sizeof address;
  ::bind(fd, reinterpret_cast<sockaddr*>(&address), size);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size);
  ::close(fd);
  return ntohs(address.sin_port);
}

// The handshake a well-behaved server plays; returns false (with a test failure) otherwise.
inline bool serve_handshake(TcpConnection& connection, const std::string& channel = "can0") {
  connection.send_text("< hi >");
  const bool opened = connection.read_message() == "< open " + channel + " >";
  EXPECT_TRUE(opened);
  if (!opened) return false;
  connection.send_text("< ok >");
  const bool raw = connection.read_message() == std::optional<std::string>("< rawmode >");
  EXPECT_TRUE(raw);
  if (raw) connection.send_text("< ok >");
  return raw;
}

}  // namespace marsokhod::bus::testing
