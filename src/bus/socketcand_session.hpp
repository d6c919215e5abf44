// One client connection of the SocketcandServer (internal to src/bus/): the socketcand state
// machine NO_BUS → BUS (after open) → RAW (after rawmode), a bounded queue of outgoing messages,
// and the handshake and raw-mode grace timers. Lives on the server's thread only.
#pragma once

#include <array>
#include <chrono>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>

#include "bus/socketcand_protocol.hpp"
#include "bus/socketcand_server.hpp"

namespace marsokhod::bus {

class SocketcandSession;

// What a session needs from its server.
class SessionHost {
 public:
  virtual const SocketcandServer::Config& config() const = 0;
  virtual void count(std::uint64_t ServerCounters::*counter) = 0;
  virtual void streaming_started() = 0;
  virtual void closed(SocketcandSession& session, bool was_streaming) = 0;
  // Hands a client's frame to the simulator (may throw: the session reports it as an error).
  virtual void frame_from_client(SocketcandSession& from, const protocol::CanFrame& frame) = 0;

 protected:
  ~SessionHost() = default;
};

class SocketcandSession : public std::enable_shared_from_this<SocketcandSession> {
 public:
  SocketcandSession(SessionHost& host, boost::asio::ip::tcp::socket socket);

  // Greets the client and starts reading.
  void start();
  // Queues a message. A droppable one (a frame) is dropped and counted when the client has
  // max_queued_bytes unread; a reply is always queued, but a client that lets replies pile up
  // beyond that is disconnected.
  void deliver(const std::string& text, bool droppable);
  // Closes the connection now; idempotent.
  void close();
  bool streaming() const { return streaming_; }

 private:
  enum class State : std::uint8_t { kNoBus, kBus, kRaw, kClosing };

  void read();
  void on_read(std::size_t size);
  void handle(const std::string& text);
  void handle_no_bus(const socketcand::Message& message);
  void handle_bus(const socketcand::Message& message);
  void handle_send(const socketcand::Send& send);
  void enter_raw_mode();
  void start_streaming();
  // Answers `< error reason >` and counts a malformed message; the connection stays.
  void reject(const std::string& reason);
  // Answers `< error reason >` and closes once it is written.
  void refuse(const std::string& reason);
  void write_next();
  // Re-arms the idle deadline (after open): called on every read and completed write.
  void touch();
  void arm_idle_timer(std::chrono::steady_clock::time_point deadline);

  SessionHost& host_;
  boost::asio::ip::tcp::socket socket_;
  boost::asio::steady_timer timer_;  // handshake deadline, then the raw-mode grace
  boost::asio::steady_timer idle_timer_;
  std::chrono::steady_clock::time_point last_activity_{};
  bool idle_armed_ = false;
  State state_ = State::kNoBus;
  bool streaming_ = false;
  bool closed_ = false;
  bool writing_ = false;
  socketcand::MessageSplitter splitter_;
  std::array<char, 4096> read_buffer_{};
  std::deque<std::string> queue_;
  std::size_t queued_bytes_ = 0;
};

}  // namespace marsokhod::bus
