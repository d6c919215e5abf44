// The wire layout shared by encode and decode (internal to core/protocol): byte order, fixed data
// lengths and bit masks of the tables in chapter 3.2–3.3 and docs/design.md's "Bit layouts".
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "core/protocol/codec.hpp"

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

inline constexpr std::array<std::uint8_t, 8> kDlc{3, 8, 5, 2, 8, 8, 1, 0};
inline constexpr std::array<const char*, 8> kNames{
    "control request",     "control response",     "configuration request", "configuration response",
    "measurement request", "measurement response", "dead man request",      "dead man response"};
// How the thesis' tables write the idt of each message type.
inline constexpr std::array<const char*, 8> kIdtPatterns{"0xi0", "0xi1", "0xi2", "0xi3",
                                                         "0x80", "0x81", "0x82", "0x83"};

// Control request byte 0.
inline constexpr std::uint8_t kDrvBit = 0x01;
inline constexpr std::uint8_t kEimBit = 0x02;
inline constexpr std::uint8_t kControlReservedBits = 0xFC;  // bits 7..2
// Control response byte 6: dir and the high 7 bits of vel.
inline constexpr std::uint8_t kDirBit = 0x80;
inline constexpr std::uint8_t kVelHighBits = 0x7F;
// Measurement request bytes 0–1: led in bit 7, ASCII in bits 6..0.
inline constexpr std::uint8_t kLedBit = 0x80;
inline constexpr std::uint8_t kAsciiBits = 0x7F;
// Measurement response b7: tlt low bits 7–6, vcc low bits 5–4, j in bit 0.
inline constexpr std::uint8_t kTiltChannelBit = 0x01;
inline constexpr std::uint8_t kStatusReservedBits = 0x0E;  // bits 3..1

}  // namespace marsokhod::protocol::wire
