#include "bus/socketcan_transport.hpp"

#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <gtest/gtest.h>

namespace marsokhod::bus {
namespace {

using std::chrono::microseconds;
using std::chrono::milliseconds;

bool kernel_has_socketcan() {
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) return false;
  ::close(fd);
  return true;
}

std::string error_of(const std::string& url) {
  try {
    open_transport(url);
  } catch (const TransportError& e) {
    return e.what();
  }
  ADD_FAILURE() << url << " opened";
  return "";
}

TEST(SocketCanTransport, WithoutKernelSupportSaysWhatToLoad) {
  if (kernel_has_socketcan()) GTEST_SKIP() << "this kernel has SocketCAN: the error cannot occur";
  EXPECT_EQ(
      error_of("socketcan:can0"),
      "cannot open socketcan:can0: the kernel has no SocketCAN support (AF_CAN): load the can "
      "and can_raw modules (modprobe can can_raw; vcan for a virtual bus), or connect to a "
      "socketcand server with socketcand://HOST:PORT/CHANNEL");
}

TEST(SocketCanTransport, MissingInterfaceSaysHowToBringItUp) {
  if (!kernel_has_socketcan()) GTEST_SKIP() << "the kernel has no SocketCAN support (AF_CAN)";
  EXPECT_EQ(
      error_of("socketcan:mk_nocan0"),
      "no CAN interface 'mk_nocan0' (it does not exist or is not a CAN device): bring it up "
      "with ip link set mk_nocan0 up type can bitrate 1000000 (a virtual bus: ip link add dev "
      "mk_nocan0 type vcan && ip link set mk_nocan0 up)");
}

TEST(SocketCanTransport, NonCanInterfaceIsRejected) {
  if (!kernel_has_socketcan()) GTEST_SKIP() << "the kernel has no SocketCAN support (AF_CAN)";
  EXPECT_NE(error_of("socketcan:lo").find("no CAN interface 'lo'"), std::string::npos);
}

TEST(SocketCanTransport, OverlongInterfaceNameIsRejected) {
  EXPECT_THROW(SocketCanTransport("sixteen_chars_00"), TransportError);
}

// A vcan interface for the duration of a test, where the kernel and our privileges allow one.
class VcanTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!kernel_has_socketcan()) GTEST_SKIP() << "the kernel has no SocketCAN support (AF_CAN)";
    name_ = "mkvcan" + std::to_string(::getpid() % 100000);
    const std::string add =
        "ip link add dev " + name_ + " type vcan 2>/dev/null && ip link set " + name_ + " up";
    if (std::system(add.c_str()) != 0) {
      GTEST_SKIP() << "cannot create a vcan interface (`ip link add dev " << name_
                   << " type vcan` failed: needs root and the vcan module)";
    }
    created_ = true;
  }
  void TearDown() override {
    if (!created_) return;
    [[maybe_unused]] const int status =
        std::system(("ip link del " + name_ + " 2>/dev/null").c_str());
  }

  std::string name_;
  bool created_ = false;
};

// Receives until `count` frames arrived or a bounded number of waits passed.
std::vector<protocol::CanFrame> receive_frames(CanTransport& transport, std::size_t count) {
  std::vector<protocol::CanFrame> frames;
  for (int i = 0; i < 50 && frames.size() < count; ++i) {
    for (const auto& f : transport.receive(milliseconds(100))) frames.push_back(f);
  }
  return frames;
}

TEST_F(VcanTest, FramesCrossTheBus) {
  SocketCanTransport sender(name_);
  SocketCanTransport receiver(name_);
  EXPECT_EQ(sender.name(), "socketcan:" + name_);
  protocol::CanFrame request;
  request.id = 0x180;
  request.dlc = 3;
  request.data = {0x03, 0x01, 0x2C};
  protocol::CanFrame empty;
  empty.id = 0x418;
  sender.send(request);
  sender.send(empty);
  const auto frames = receive_frames(receiver, 2);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0], request);
  EXPECT_EQ(frames[1], empty);
  EXPECT_EQ(sender.counters().frames_sent, 2u);
  EXPECT_EQ(receiver.counters().frames_received, 2u);
  EXPECT_TRUE(sender.receive(microseconds(0)).empty());  // no echo of one's own frames
}

TEST_F(VcanTest, ExtendedFramesAreCountedNotReturned) {
  SocketCanTransport receiver(name_);
  const int raw = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
  sockaddr_can address{};
  address.can_family = AF_CAN;
  address.can_ifindex = static_cast<int>(::if_nametoindex(name_.c_str()));
  ASSERT_EQ(::bind(raw, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
  can_frame extended{};
  extended.can_id = 0x1AAAAAAA | CAN_EFF_FLAG;
  extended.len = 1;
  ASSERT_EQ(::write(raw, &extended, sizeof extended), static_cast<ssize_t>(sizeof extended));
  ::close(raw);
  for (int i = 0; i < 50 && receiver.counters().ignored == 0; ++i) {
    EXPECT_TRUE(receiver.receive(milliseconds(100)).empty());
  }
  EXPECT_EQ(receiver.counters().ignored, 1u);
}

TEST_F(VcanTest, ReceiveReturnsEmptyAfterTheTimeout) {
  SocketCanTransport receiver(name_);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_TRUE(receiver.receive(milliseconds(20)).empty());
  EXPECT_GE(std::chrono::steady_clock::now() - start, milliseconds(19));
}

TEST_F(VcanTest, InvalidFramesAreNotSent) {
  SocketCanTransport sender(name_);
  protocol::CanFrame frame;
  frame.id = 0x800;
  EXPECT_THROW(sender.send(frame), TransportError);
  frame.id = 0x180;
  frame.dlc = 9;
  EXPECT_THROW(sender.send(frame), TransportError);
}

}  // namespace
}  // namespace marsokhod::bus
