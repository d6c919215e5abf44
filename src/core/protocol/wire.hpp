// The wire layout shared by encode and decode (internal to core/protocol): byte order, fixed data
// lengths and bit masks of the tables in chapter 3.2–3.3, taken from wire_layout.h, the C header
// the firmware (firmware/) compiles too.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "core/protocol/codec.hpp"
#include "core/protocol/wire_layout.h"

namespace marsokhod::protocol::wire {

using Data = std::array<std::uint8_t, 8>;

// The thesis' tables list _h before _l: big-endian.
constexpr std::uint16_t read_u16(const Data& data, std::size_t at) {
  return static_cast<std::uint16_t>((data[at] << 8) | data[at + 1]);
}

constexpr void write_u16(Data& data, std::size_t at, std::uint16_t value) {
  data[at] = static_cast<std::uint8_t>(value >> 8);
  data[at + 1] = static_cast<std::uint8_t>(value & 0xFF);
}

constexpr bool is_sensor(std::uint8_t node) { return node == kSensorController; }

// Index into Message (and kNames, kDlc): the variant lists the four motor-controller messages
// in type order, then µ8's four.
constexpr std::size_t message_index(std::uint8_t node, std::uint8_t type) {
  return (is_sensor(node) ? 4U : 0U) + type;
}

inline constexpr std::array<std::uint8_t, 8> kDlc{
    MK_DLC_CONTROL_REQUEST,     MK_DLC_CONTROL_RESPONSE,     MK_DLC_CONFIGURATION_REQUEST,
    MK_DLC_CONFIGURATION_RESPONSE, MK_DLC_MEASUREMENT_REQUEST, MK_DLC_MEASUREMENT_RESPONSE,
    MK_DLC_DEAD_MAN_REQUEST,    MK_DLC_DEAD_MAN_RESPONSE};
inline constexpr std::array<const char*, 8> kNames{
    "control request",     "control response",     "configuration request", "configuration response",
    "measurement request", "measurement response", "dead man request",      "dead man response"};
// How the thesis' tables write the idt of each message type.
inline constexpr std::array<const char*, 8> kIdtPatterns{"0xi0", "0xi1", "0xi2", "0xi3",
                                                         "0x80", "0x81", "0x82", "0x83"};

// Control request byte 0.
inline constexpr std::uint8_t kDrvBit = MK_DRV_BIT;
inline constexpr std::uint8_t kEimBit = MK_EIM_BIT;
inline constexpr std::uint8_t kControlReservedBits = MK_CONTROL_RESERVED_BITS;
// Control response byte 6: dir and the high 7 bits of vel.
inline constexpr std::uint8_t kDirBit = MK_DIR_BIT;
inline constexpr std::uint8_t kVelHighBits = MK_VEL_HIGH_BITS;
// Measurement request bytes 0–1: led in bit 7, ASCII in bits 6..0.
inline constexpr std::uint8_t kLedBit = MK_LED_BIT;
inline constexpr std::uint8_t kAsciiBits = MK_ASCII_BITS;
// Measurement response b7: tlt low bits 7–6, vcc low bits 5–4, j in bit 0.
inline constexpr std::uint8_t kTiltChannelBit = MK_TILT_CHANNEL_BIT;
inline constexpr std::uint8_t kStatusReservedBits = MK_STATUS_RESERVED_BITS;

}  // namespace marsokhod::protocol::wire
