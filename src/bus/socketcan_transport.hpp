// A CAN interface of the Linux kernel (SocketCAN): a raw CAN socket (PF_CAN, SOCK_RAW, CAN_RAW)
// bound to one interface by name. Classic frames only: the socket never enables CAN FD, and
// remote, error and extended frames that reach it are counted as ignored.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "bus/transport.hpp"

namespace marsokhod::bus {

class SocketCanTransport final : public CanTransport {
 public:
  // Throws TransportError naming what is missing: kernel support (AF_CAN), the interface, or the
  // permission to use it.
  explicit SocketCanTransport(const std::string& interface);
  ~SocketCanTransport() override;
  SocketCanTransport(const SocketCanTransport&) = delete;
  SocketCanTransport& operator=(const SocketCanTransport&) = delete;

  void send(const protocol::CanFrame& frame) override;
  std::vector<protocol::CanFrame> receive(std::chrono::microseconds timeout) override;
  std::string name() const override { return "socketcan:" + interface_; }
  TransportCounters counters() const override { return counters_; }

 private:
  // Reads every frame already queued on the socket without waiting.
  void drain(std::vector<protocol::CanFrame>& out);

  std::string interface_;
  int fd_ = -1;
  TransportCounters counters_;
};

}  // namespace marsokhod::bus
