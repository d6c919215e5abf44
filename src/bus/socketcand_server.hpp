// A socketcand server for `marsokhod sim`: the emulated bus, reachable by our SocketcandClient,
// by python-can's `socketcand` interface and by any other socketcand client.
//
// Per client: `< hi >` on connect; `< open CHANNEL >` → `< ok >` for the configured channel, else
// `< error … >` and the connection is closed (as socketcand does); `< rawmode >` → `< ok >`; then
// `< send … >` frames go to on_frame (and, as on a real bus, to the other clients), and frames
// given to broadcast() go to every client in raw mode as `< frame … >`. Malformed messages are
// answered with `< error REASON >` and counted; they never end the connection — except bytes
// outside `< … >` before a successful open, and an HTTP request line at any time, which close it
// at once: any web page can make the operator's browser POST to 127.0.0.1:29536, and its body's
// `< open >< send … >` must never reach the bus. An opened connection that neither sends nor
// takes anything for idle_timeout is closed too, so that idle clients cannot hold every slot.
//
// The io_context runs on the server's own thread between start() and stop(). Bounded: clients
// (max_clients), the time to open a channel (handshake_timeout), every message
// (socketcand::kMaxMessageLength) and the bytes queued per client (max_queued_bytes; frames
// beyond are dropped for that slow client and counted).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "bus/transport.hpp"

namespace marsokhod::bus {

struct ServerCounters {
  std::uint64_t clients_accepted = 0;
  std::uint64_t clients_refused = 0;      // too many clients, wrong channel, handshake timeout,
                                          // stray bytes before open, HTTP, idle
  std::uint64_t frames_from_clients = 0;  // `< send … >` passed to on_frame
  std::uint64_t frames_broadcast = 0;     // broadcast() calls while running
  std::uint64_t malformed_messages = 0;   // client messages answered with `< error … >`
  std::uint64_t frames_dropped = 0;       // frames not queued for a client that does not read
  std::size_t streaming_clients = 0;      // clients now receiving frames
};

class SocketcandServer {
 public:
  struct Config {
    std::string address = "127.0.0.1";            // an IPv4 or IPv6 address to listen on
    std::uint16_t port = kSocketcandDefaultPort;  // 0: an ephemeral port, see port()
    std::string channel = kSocketcandDefaultChannel;
    std::size_t max_clients = 8;
    std::chrono::milliseconds handshake_timeout{10000};  // connect → successful open
    // After open: no byte read and no write completed for this long ⇒ closed.
    std::chrono::milliseconds idle_timeout{60000};
    // python-can reads each handshake reply with a single recv() and compares it exactly, so a
    // frame glued to the rawmode `< ok >` would break its handshake. A client receives frames
    // once it sends its first message after raw mode, or after this grace.
    std::chrono::milliseconds rawmode_grace{50};
    std::size_t max_queued_bytes = 256 * 1024;
    // A frame one client sends also reaches the other clients (with the server's wall-clock
    // time), as every node sees every frame on a real bus; never echoed to its sender.
    bool relay_between_clients = true;
  };

  // Called on the server's thread for every frame a client sends; may call broadcast(), must not
  // call stop() and should return quickly (it delays every client). An exception it throws is
  // reported to that client as `< error … >`.
  using FrameCallback = std::function<void(const protocol::CanFrame&)>;

  SocketcandServer(Config config, FrameCallback on_frame);
  ~SocketcandServer();  // stop()
  SocketcandServer(const SocketcandServer&) = delete;
  SocketcandServer& operator=(const SocketcandServer&) = delete;

  // Listens and starts the thread. Throws TransportError when the address is not an address or
  // the port is taken. Once only.
  void start();
  // Closes every connection and joins the thread. Idempotent; safe without start().
  void stop();
  // The port listened on (the ephemeral one when Config::port was 0); 0 before start().
  std::uint16_t port() const;

  // Thread-safe. Sends `< frame … >` stamped with time_s to every streaming client. Throws
  // std::invalid_argument for a frame the protocol cannot carry (id > 0x7FF, DLC > 8) or a time
  // that is negative or not finite. Ignored when not running.
  void broadcast(const protocol::CanFrame& frame, double time_s);

  // Waits until at least `count` clients are streaming (raw mode, grace over), at most `timeout`.
  bool wait_for_streaming_clients(std::size_t count, std::chrono::milliseconds timeout) const;

  ServerCounters counters() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace marsokhod::bus
