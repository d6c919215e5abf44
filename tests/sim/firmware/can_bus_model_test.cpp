#include "sim/firmware/can_bus_model.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "core/protocol/codec.hpp"

namespace marsokhod::sim {
namespace {

using protocol::CanFrame;

std::vector<bool> ascii_bits(const std::string& text) {
  std::vector<bool> bits;
  for (const char c : text) {
    for (int bit = 7; bit >= 0; --bit) {
      bits.push_back(((static_cast<unsigned char>(c) >> bit) & 1U) != 0);
    }
  }
  return bits;
}

std::string bit_string(const std::vector<bool>& bits) {
  std::string text;
  for (const bool bit : bits) {
    text += bit ? '1' : '0';
  }
  return text;
}

TEST(SimCanBusModel, Crc15HasTheCatalogueCheckValue) {
  // CRC-15/CAN (poly 0x4599, init 0, no reflection) of "123456789" is 0x059E.
  EXPECT_EQ(can_crc15(ascii_bits("123456789")), 0x059E);
}

TEST(SimCanBusModel, EightByteFrameWithoutStuffingTakes111Bits) {
  // id 0x2AA = 01010101010, DLC 1000, data 0xAA…: no run of five anywhere, CRC 0x43D6 =
  // 100001111010110 neither. 47 + 64 = 111 bits = 111 µs; receivers have it after 108 µs.
  CanFrame frame{0x2AA, 8, {0xAA, 0xAA, 0xAA, 0xAA, 0xAA, 0xAA, 0xAA, 0xAA}};
  const std::vector<bool> bits = frame_bits_before_stuffing(frame);
  EXPECT_EQ(bits.size(), 19U + 64U + 15U);
  EXPECT_EQ(bit_string(bits).substr(83), "100001111010110");
  const FrameTiming timing = frame_timing(frame);
  EXPECT_EQ(timing.stuff_bits, 0);
  EXPECT_EQ(timing.total_bits, 111);
  EXPECT_EQ(timing.duration_ns(), 111'000);
  EXPECT_EQ(timing.delivery_after_ns(), 108'000);
}

TEST(SimCanBusModel, DeadManResponseHasFiveStuffBits) {
  // 0x83 → CAN ID 0x418, DLC 0. SOF..DLC = 0 10000011000 000 0000, CRC 0x027D =
  // 000001001111101. Stuffed (stuff bits in brackets):
  //   0 1 00000[1] 11 00000[1] 00000[1] 00000[1] 1 00 11111[0] 01
  // 34 + 5 bits, and 47 + 5 = 52 bits on the wire.
  const CanFrame frame = protocol::encode(protocol::DeadManResponse{});
  EXPECT_EQ(frame.id, 0x418U);
  EXPECT_EQ(bit_string(frame_bits_before_stuffing(frame)), "0100000110000000000000001001111101");
  EXPECT_EQ(stuff_bit_count(frame_bits_before_stuffing(frame)), 5);
  EXPECT_EQ(frame_timing(frame).total_bits, 52);
}

TEST(SimCanBusModel, ProtocolFramesOfHandWorkedLength) {
  // µ8's dog = 4 (0x82 → 0x410, 1 byte): 55 + 4 stuff bits.
  EXPECT_EQ(frame_timing(protocol::encode(protocol::DeadManRequest{4})).total_bits, 59);
  // µ8's stop frame to µ0: id 0, bytes 02 00 00: long zero runs, 71 + 8 stuff bits.
  const CanFrame stop = protocol::encode(protocol::ControlRequest{0, false, true, 0});
  EXPECT_EQ(bit_string(frame_bits_before_stuffing(stop)),
            "0000000000000000011000000100000000000000000000011010111001");
  EXPECT_EQ(frame_timing(stop).total_bits, 79);
  // The worst case: all 34 bits of id 0, DLC 0 and CRC 0 dominant, a stuff bit every 5.
  EXPECT_EQ(frame_timing(CanFrame{0, 0, {}}).total_bits, 47 + 6);
}

TEST(SimCanBusModel, LowestIdentifierWinsArbitration) {
  CanBusModel bus;
  bus.enqueue(CanFrame{0x100, 0, {}}, 0);
  bus.enqueue(CanFrame{0x008, 0, {}}, 0, 0);
  bus.enqueue(CanFrame{0x400, 0, {}}, 0, 8);
  const std::vector<BusDelivery> deliveries = bus.run_until(1'000'000);
  ASSERT_EQ(deliveries.size(), 3U);
  EXPECT_EQ(deliveries[0].frame.id, 0x008U);
  EXPECT_EQ(deliveries[1].frame.id, 0x100U);
  EXPECT_EQ(deliveries[2].frame.id, 0x400U);
  EXPECT_EQ(deliveries[0].start_ns, 0);
  for (std::size_t i = 1; i < deliveries.size(); ++i) {
    EXPECT_EQ(deliveries[i].start_ns, deliveries[i - 1].bus_free_ns);
    EXPECT_EQ(deliveries[i].delivery_ns,
              deliveries[i].start_ns + frame_timing(deliveries[i].frame).delivery_after_ns());
  }
}

TEST(SimCanBusModel, FrameReadyDuringATransmissionWaitsForTheBus) {
  CanBusModel bus;
  bus.enqueue(CanFrame{0x400, 8, {}}, 0);
  bus.enqueue(CanFrame{0x000, 0, {}}, 10'000);  // higher priority, but too late for SOF
  const BusDelivery first = bus.pop();
  EXPECT_EQ(first.frame.id, 0x400U);
  const BusDelivery second = bus.pop();
  EXPECT_EQ(second.start_ns, first.bus_free_ns);
  // An idle bus starts a frame when it is ready.
  bus.enqueue(CanFrame{0x123, 1, {7}}, 5'000'000);
  EXPECT_EQ(bus.pop().start_ns, 5'000'000);
}

TEST(SimCanBusModel, ControlCycleTakesAboutOnePointSevenMilliseconds) {
  CanBusModel bus;
  for (std::uint8_t node = 0; node < 8; ++node) {
    bus.enqueue(protocol::encode(protocol::ControlRequest{node, false, true, 200}), 0);
    bus.enqueue(protocol::encode(protocol::ControlResponse{node, 12345, 4321, 100, false, 777}), 0,
                node);
  }
  bus.enqueue(protocol::encode(protocol::MeasurementRequest{}), 0);
  protocol::MeasurementResponse typ;
  typ.yaw = 505;
  typ.acc = {279, 251, 376};
  typ.tlt = 527;
  typ.vcc = 970;
  bus.enqueue(protocol::encode(typ), 0, 8);
  const std::vector<BusDelivery> deliveries = bus.run_until(10'000'000);
  ASSERT_EQ(deliveries.size(), 18U);
  SimTimeNs expected_ns = 0;
  for (const BusDelivery& delivery : deliveries) {
    expected_ns += frame_timing(delivery.frame).duration_ns();
  }
  EXPECT_EQ(deliveries.back().bus_free_ns, expected_ns);  // back to back, no gap
  EXPECT_GT(expected_ns, 1'600'000);
  EXPECT_LT(expected_ns, 1'850'000);
}

TEST(SimCanBusModel, FrameLossIsSeeded) {
  const auto lost_pattern = [](std::uint64_t seed) {
    CanBusModel bus(seed);
    bus.set_frame_loss_probability(0.3);
    std::string pattern;
    for (int i = 0; i < 200; ++i) {
      bus.enqueue(CanFrame{0x100, 0, {}}, i * 100'000);
      pattern += bus.pop().lost ? 'x' : '.';
    }
    return pattern;
  };
  EXPECT_EQ(lost_pattern(1), lost_pattern(1));
  EXPECT_NE(lost_pattern(1), lost_pattern(2));
  const std::string pattern = lost_pattern(1);
  const auto lost = std::count(pattern.begin(), pattern.end(), 'x');
  EXPECT_GT(lost, 30);
  EXPECT_LT(lost, 90);
  CanBusModel bus;
  EXPECT_THROW(bus.set_frame_loss_probability(1.5), std::invalid_argument);
  EXPECT_THROW(bus.enqueue(CanFrame{0x800, 0, {}}, 0), std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::sim
