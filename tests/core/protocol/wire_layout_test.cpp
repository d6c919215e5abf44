// wire_layout.h, the C header the firmware shares with the codec: its constants are the codec's,
// its offsets are where encode puts the fields (a frame built by hand from the offsets decodes to
// the message), and every message round-trips.
#include "core/protocol/wire_layout.h"

#include <gtest/gtest.h>

#include <variant>

#include "core/protocol/codec.hpp"

namespace marsokhod::protocol {
namespace {

static_assert(MK_CAN_ID(3, MK_TYPE_CONTROL_REQUEST) == 0x180);  // idt 0x30, docs/design.md
static_assert(MK_CAN_ID(MK_SENSOR_NODE, MK_TYPE_DEAD_MAN_RESPONSE) == 0x418);
static_assert(kDeadManTickUs == 65536LL * 64 * 1'000'000 / 16'000'000);  // Timer 1, 16 MHz/64

void put_u16(CanFrame& frame, int at, unsigned value) {
  frame.data[static_cast<std::size_t>(at)] = static_cast<std::uint8_t>(value >> 8);
  frame.data[static_cast<std::size_t>(at) + 1] = static_cast<std::uint8_t>(value & 0xFF);
}

TEST(WireLayout, ControlResponseBuiltFromTheOffsetsDecodes) {
  CanFrame frame;
  frame.id = MK_CAN_ID(5, MK_TYPE_CONTROL_RESPONSE);
  frame.dlc = MK_DLC_CONTROL_RESPONSE;
  put_u16(frame, MK_CONTROL_RESPONSE_TIM, 0xBEEF);
  put_u16(frame, MK_CONTROL_RESPONSE_ENC, 40000);
  put_u16(frame, MK_CONTROL_RESPONSE_STP, 1234);
  frame.data[MK_CONTROL_RESPONSE_DIR_VEL] = MK_DIR_BIT | (0x5432 >> 8);
  frame.data[MK_CONTROL_RESPONSE_VEL_LOW] = 0x32;
  const DecodeResult decoded = decode(frame);
  ASSERT_TRUE(decoded.ok()) << decoded.error().reason;
  EXPECT_EQ(std::get<ControlResponse>(decoded.message()),
            (ControlResponse{5, 0xBEEF, 40000, 1234, true, 0x5432}));
  EXPECT_EQ(encode(decoded.message()), frame);
}

TEST(WireLayout, RequestsEncodeAtTheOffsets) {
  const CanFrame control = encode(ControlRequest{2, true, true, 300});
  EXPECT_EQ(control.id, static_cast<std::uint32_t>(MK_CAN_ID(2, MK_TYPE_CONTROL_REQUEST)));
  EXPECT_EQ(control.dlc, MK_DLC_CONTROL_REQUEST);
  EXPECT_EQ(control.data[MK_CONTROL_REQUEST_FLAGS], MK_DRV_BIT | MK_EIM_BIT);
  EXPECT_EQ(control.data[MK_CONTROL_REQUEST_PWM], 300 >> 8);
  EXPECT_EQ(control.data[MK_CONTROL_REQUEST_PWM + 1], 300 & 0xFF);

  const CanFrame config = encode(ConfigurationRequest{7, 1023, 17, 9});
  EXPECT_EQ(config.dlc, MK_DLC_CONFIGURATION_REQUEST);
  EXPECT_EQ(config.data[MK_CONFIGURATION_REQUEST_ICR + 1], 1023 & 0xFF);
  EXPECT_EQ(config.data[MK_CONFIGURATION_REQUEST_PWM + 1], 17);
  EXPECT_EQ(config.data[MK_CONFIGURATION_REQUEST_CON], 9);

  const CanFrame dog = encode(DeadManRequest{42});
  EXPECT_EQ(dog.id, static_cast<std::uint32_t>(MK_CAN_ID(MK_SENSOR_NODE, MK_TYPE_DEAD_MAN_REQUEST)));
  EXPECT_EQ(dog.data[MK_DEAD_MAN_REQUEST_DOG], 42);
}

TEST(WireLayout, MeasurementResponseLowBitsAndChannel) {
  MeasurementResponse response{1023, {1, 2, 3}, 514, 970, TiltChannel::kRear};
  const CanFrame frame = encode(response);
  EXPECT_EQ(frame.dlc, MK_DLC_MEASUREMENT_RESPONSE);
  EXPECT_EQ(frame.data[0], 1023 >> 2);
  // yaw 1023 → 11 in bits 7–6; acc 1, 2, 3 → 01, 10, 11.
  EXPECT_EQ(frame.data[MK_MEASUREMENT_LOW_BITS_1], 0b11'01'10'11);
  // tlt 514 → 10, vcc 970 → 10, j = 1.
  EXPECT_EQ(frame.data[MK_MEASUREMENT_LOW_BITS_2], (0b10 << 6) | (0b10 << 4) | MK_TILT_CHANNEL_BIT);
  EXPECT_EQ(frame.data[MK_MEASUREMENT_LOW_BITS_2] & MK_STATUS_RESERVED_BITS, 0);
  EXPECT_EQ(std::get<MeasurementResponse>(decode(frame).message()), response);
}

TEST(WireLayout, RangesAreTheCodecs) {
  EXPECT_THROW((void)encode(ConfigurationRequest{0, MK_ICR_MIN - 1, 0, 0}), std::invalid_argument);
  EXPECT_NO_THROW((void)encode(ConfigurationRequest{0, MK_ICR_MAX, MK_ICR_MAX, 0}));
  EXPECT_THROW((void)encode(ConfigurationRequest{0, MK_ICR_MAX + 1, 0, 0}), std::invalid_argument);
  EXPECT_THROW((void)encode(ControlResponse{0, 0, 0, 0, false, MK_VEL_MAX + 1}),
               std::invalid_argument);
  EXPECT_EQ(ConfigurationRequest{}.icr, MK_ICR_RESET);
}

}  // namespace
}  // namespace marsokhod::protocol
