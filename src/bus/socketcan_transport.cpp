#include "bus/socketcan_transport.hpp"

#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

namespace marsokhod::bus {
namespace {

// A bounded burst per receive() keeps one call's latency bounded even on a saturated bus.
constexpr int kMaxFramesPerReceive = 1024;
// How long send() keeps trying while the interface's transmit queue is full: long enough to
// ride out a burst, short enough for the control loop to notice a dead bus within one period.
constexpr std::chrono::milliseconds kSendDeadline{50};

std::string errno_message(int err) {
  return std::error_code(err, std::generic_category()).message();
}

std::string bring_up_hint(const std::string& interface) {
  return "bring it up with ip link set " + interface +
         " up type can bitrate 1000000 (a virtual "
         "bus: ip link add dev " +
         interface + " type vcan && ip link set " + interface + " up)";
}

[[noreturn]] void fail_interface(const std::string& interface, int err) {
  if (err == ENODEV) {
    throw TransportError("no CAN interface '" + interface +
                         "' (it does not exist or is not a CAN "
                         "device): " +
                         bring_up_hint(interface));
  }
  if (err == ENETDOWN) {
    throw TransportError("CAN interface '" + interface + "' is down: " + bring_up_hint(interface));
  }
  if (err == EPERM || err == EACCES) {
    throw TransportError("no permission to use CAN interface '" + interface + "' (" +
                         errno_message(err) + "): run with CAP_NET_RAW or as root");
  }
  throw TransportError("CAN interface '" + interface + "': " + errno_message(err));
}

int open_raw_socket(const std::string& interface) {
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC | SOCK_NONBLOCK, CAN_RAW);
  if (fd >= 0) return fd;
  const int err = errno;
  if (err == EAFNOSUPPORT || err == EPROTONOSUPPORT) {
    throw TransportError("cannot open socketcan:" + interface +
                         ": the kernel has no SocketCAN support (AF_CAN): load the can and can_raw "
                         "modules (modprobe can can_raw; vcan for a virtual bus), or connect to a "
                         "socketcand server with socketcand://HOST:PORT/CHANNEL");
  }
  fail_interface(interface, err);
}

}  // namespace

SocketCanTransport::SocketCanTransport(const std::string& interface) : interface_(interface) {
  if (interface.empty() || interface.size() >= IFNAMSIZ) {
    throw TransportError("CAN interface name '" + interface + "' must have 1–" +
                         std::to_string(IFNAMSIZ - 1) + " characters");
  }
  fd_ = open_raw_socket(interface);
  const unsigned index = ::if_nametoindex(interface.c_str());
  const int lookup_error = errno;
  sockaddr_can address{};
  address.can_family = AF_CAN;
  address.can_ifindex = static_cast<int>(index);
  if (index == 0 || ::bind(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    const int err = index == 0 ? lookup_error : errno;
    ::close(fd_);
    fd_ = -1;
    fail_interface(interface, err);
  }
}

SocketCanTransport::~SocketCanTransport() {
  if (fd_ >= 0) ::close(fd_);
}

void SocketCanTransport::send(const protocol::CanFrame& frame) {
  if (frame.id > CAN_SFF_MASK || frame.dlc > CAN_MAX_DLEN) {
    throw TransportError("cannot send to " + name() + ": " + describe_frame(frame) +
                         " is not a classic frame (11-bit identifier, at most 8 bytes)");
  }
  can_frame raw{};
  raw.can_id = frame.id;
  raw.len = frame.dlc;
  std::memcpy(raw.data, frame.data.data(), frame.dlc);
  const auto deadline = std::chrono::steady_clock::now() + kSendDeadline;
  while (true) {
    if (::send(fd_, &raw, sizeof raw, MSG_DONTWAIT) == static_cast<ssize_t>(sizeof raw)) {
      ++counters_.frames_sent;
      return;
    }
    const int err = errno;
    if (err != EINTR && err != EAGAIN && err != ENOBUFS) fail_interface(interface_, err);
    if (std::chrono::steady_clock::now() >= deadline) {
      throw TransportError("transmit queue of CAN interface '" + interface_ + "' stays full (" +
                           errno_message(err) +
                           "): is another node acknowledging frames (bus "
                           "connected, terminated with 120 Ω, same bitrate)?");
    }
    // ENOBUFS is the qdisc being full, which poll() does not report: wait a millisecond instead.
    pollfd writable{fd_, POLLOUT, 0};
    ::poll(&writable, err == EAGAIN ? 1 : 0, 1);
  }
}

std::vector<protocol::CanFrame> SocketCanTransport::receive(std::chrono::microseconds timeout) {
  std::vector<protocol::CanFrame> frames;
  drain(frames);
  if (!frames.empty() || timeout <= std::chrono::microseconds::zero()) return frames;
  pollfd readable{fd_, POLLIN, 0};
  const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(timeout);
  const timespec wait{static_cast<time_t>(seconds.count()),
                      static_cast<long>((timeout - seconds).count() * 1000)};
  // EINTR ends the wait early, which the contract allows ("never blocks longer").
  if (::ppoll(&readable, 1, &wait, nullptr) > 0) drain(frames);
  return frames;
}

void SocketCanTransport::drain(std::vector<protocol::CanFrame>& out) {
  for (int i = 0; i < kMaxFramesPerReceive; ++i) {
    canfd_frame raw{};
    const ssize_t size = ::recv(fd_, &raw, sizeof raw, MSG_DONTWAIT);
    if (size < 0) {
      const int err = errno;
      if (err == EINTR) continue;
      if (err == EAGAIN || err == EWOULDBLOCK) return;
      fail_interface(interface_, err);
    }
    if (size == static_cast<ssize_t>(CANFD_MTU)) {
      ++counters_.ignored;
      continue;
    }
    if (size != static_cast<ssize_t>(CAN_MTU) || raw.len > CAN_MAX_DLEN) {
      ++counters_.malformed_dropped;
      continue;
    }
    if ((raw.can_id & (CAN_ERR_FLAG | CAN_RTR_FLAG | CAN_EFF_FLAG)) != 0) {
      ++counters_.ignored;
      continue;
    }
    protocol::CanFrame frame;
    frame.id = raw.can_id & CAN_SFF_MASK;
    frame.dlc = raw.len;
    std::memcpy(frame.data.data(), raw.data, raw.len);
    out.push_back(frame);
    ++counters_.frames_received;
  }
}

}  // namespace marsokhod::bus
