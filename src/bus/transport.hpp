// One interface for every way a CAN frame reaches the rover's bus: a SocketCAN interface of the
// kernel ("socketcan:can0") or a socketcand server over TCP ("socketcand://127.0.0.1:29536/can0"),
// which is how `marsokhod sim` exposes its emulated bus.
//
// Only classic CAN 2.0A data frames (11-bit identifier, 0–8 bytes) are ours; anything else seen on
// the bus (CAN FD, remote, error or extended frames) is counted and dropped, never returned.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/protocol/can_frame.hpp"

namespace marsokhod::bus {

struct TimedFrame {
  double time_s = 0.0;
  protocol::CanFrame frame;
};

// Every failure a user can meet (no kernel support, interface down, server unreachable, bad URL).
// The message says what was wrong and what to do.
class TransportError : public std::runtime_error {
 public:
  using runtime_error::runtime_error;
};

// For the status display: a growing malformed_dropped or peer_errors count points at the wiring or
// at a peer speaking another dialect, long before the controllers notice missing frames.
struct TransportCounters {
  std::uint64_t frames_sent = 0;
  std::uint64_t frames_received = 0;
  std::uint64_t malformed_dropped = 0;  // received lines or frames that could not be parsed
  std::uint64_t ignored = 0;            // well formed, not ours: FD, remote, error, extended frames
  std::uint64_t peer_errors = 0;        // `< error … >` reports from a socketcand server
};

class CanTransport {
 public:
  virtual ~CanTransport() = default;
  // Throws TransportError when the frame cannot be put on the bus (or is not a classic 11-bit
  // frame with DLC ≤ 8).
  virtual void send(const protocol::CanFrame& frame) = 0;
  // Waits up to `timeout` for frames; returns what arrived (possibly none). Never blocks longer.
  // Throws TransportError when the bus went away (interface down, server closed the connection).
  virtual std::vector<protocol::CanFrame> receive(std::chrono::microseconds timeout) = 0;
  // "socketcan:can0", "socketcand://127.0.0.1:29536/can0".
  virtual std::string name() const = 0;
  virtual TransportCounters counters() const = 0;
};

struct TransportUrl {
  enum class Kind : std::uint8_t { kSocketCan, kSocketcand };
  Kind kind = Kind::kSocketCan;
  std::string interface;  // socketcan: the kernel interface, e.g. "can0"
  std::string host;       // socketcand: name or address (IPv6 without the brackets)
  std::uint16_t port = 0;
  std::string channel;  // socketcand: the bus to open on the server
};

inline constexpr std::uint16_t kSocketcandDefaultPort = 29536;
inline constexpr const char* kSocketcandDefaultChannel = "can0";

// "socketcan:IFACE" | "socketcand://HOST[:PORT][/CHANNEL]" (PORT default 29536, CHANNEL default
// can0; an IPv6 HOST in brackets: socketcand://[::1]:29536/can0). Throws TransportError naming the
// expected form when the URL is malformed.
TransportUrl parse_transport_url(const std::string& url);

// "id 0x180, DLC 3": for error messages about a frame.
std::string describe_frame(const protocol::CanFrame& frame);

// Opens (and, for socketcand, connects and handshakes) the transport the URL names.
std::unique_ptr<CanTransport> open_transport(const std::string& url);

}  // namespace marsokhod::bus
