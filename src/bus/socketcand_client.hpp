// A CanTransport over TCP to a socketcand server (linux-can/socketcand, or `marsokhod sim`'s
// SocketcandServer): connects, greets (< hi >, < open CHANNEL >, < rawmode >), then sends frames
// as `< send … >` and receives `< frame … >`. Every wait has a deadline; nothing blocks longer.
// Not thread-safe: one thread sends and receives.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bus/transport.hpp"

namespace marsokhod::bus {

class SocketcandClient final : public CanTransport {
 public:
  struct Config {
    std::string host = "127.0.0.1";  // an address, or a name resolved by the system resolver
    std::uint16_t port = kSocketcandDefaultPort;
    std::string channel = kSocketcandDefaultChannel;
    std::chrono::milliseconds connect_timeout{3000};
    std::chrono::milliseconds handshake_timeout{3000};  // for each reply of the server
    std::chrono::milliseconds send_timeout{1000};       // a server that stops reading
  };

  // Connects and completes the handshake; throws TransportError saying what failed (refused,
  // timed out, not a socketcand server, channel refused) and what to check.
  explicit SocketcandClient(Config config);
  ~SocketcandClient() override;
  SocketcandClient(const SocketcandClient&) = delete;
  SocketcandClient& operator=(const SocketcandClient&) = delete;

  void send(const protocol::CanFrame& frame) override;
  std::vector<protocol::CanFrame> receive(std::chrono::microseconds timeout) override;
  std::string name() const override;
  TransportCounters counters() const override;

  // The text of the latest `< error … >` from the server ("" if none): the server's reason for
  // rejecting a frame we sent.
  std::string last_peer_error() const;

 private:
  struct Impl;  // keeps Boost.Asio out of every includer
  std::unique_ptr<Impl> impl_;
};

}  // namespace marsokhod::bus
