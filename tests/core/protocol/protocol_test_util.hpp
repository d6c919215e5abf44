// Helpers shared by the protocol tests: frames written as byte lists, random valid messages.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <ostream>
#include <random>

#include "core/protocol/codec.hpp"

namespace marsokhod::protocol {

// Readable failures: "0x180 [3] 03 01 2C".
inline void PrintTo(const CanFrame& frame, std::ostream* out) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  *out << "0x" << kDigits[(frame.id >> 8) & 0xF] << kDigits[(frame.id >> 4) & 0xF]
       << kDigits[frame.id & 0xF] << " [" << static_cast<int>(frame.dlc) << "]";
  for (std::size_t i = 0; i < frame.data.size() && i < frame.dlc; ++i) {
    *out << ' ' << kDigits[frame.data[i] >> 4] << kDigits[frame.data[i] & 0xF];
  }
}

}  // namespace marsokhod::protocol

namespace marsokhod::protocol::test {

// A frame whose DLC is the number of bytes given; the rest of the data stays zero.
inline CanFrame make_frame(std::uint32_t id, std::initializer_list<std::uint8_t> bytes) {
  CanFrame frame;
  frame.id = id;
  frame.dlc = static_cast<std::uint8_t>(bytes.size());
  std::size_t i = 0;
  for (const std::uint8_t byte : bytes) {
    frame.data[i++] = byte;
  }
  return frame;
}

inline unsigned uniform(std::mt19937& rng, unsigned low, unsigned high) {
  return std::uniform_int_distribution<unsigned>(low, high)(rng);
}

inline std::uint8_t u8(std::mt19937& rng, unsigned low = 0, unsigned high = 0xFF) {
  return static_cast<std::uint8_t>(uniform(rng, low, high));
}

inline std::uint16_t u16(std::mt19937& rng, unsigned low = 0, unsigned high = 0xFFFF) {
  return static_cast<std::uint16_t>(uniform(rng, low, high));
}

inline bool bit(std::mt19937& rng) { return uniform(rng, 0, 1) == 1; }

// A message of the variant alternative `index` (0..7) with every field drawn from its legal range.
inline Message random_message(std::mt19937& rng, std::size_t index) {
  const std::uint8_t node = u8(rng, 0, kMotorControllerCount - 1);
  switch (index) {
    case 0: return ControlRequest{node, bit(rng), bit(rng), u16(rng, 0, kMaxIcr)};
    case 1:
      return ControlResponse{node, u16(rng), u16(rng), u16(rng), bit(rng), u16(rng, 0, kMaxVel)};
    case 2: {
      const std::uint16_t icr = u16(rng, kMinIcr, kMaxIcr);
      return ConfigurationRequest{node, icr, u16(rng, 0, icr), u8(rng)};
    }
    case 3: return ConfigurationResponse{node, u16(rng)};
    case 4: {
      MeasurementRequest message{bit(rng), bit(rng), {}};
      for (char& c : message.lcd) {
        c = static_cast<char>(uniform(rng, kMinLcdChar, kMaxLcdChar));
      }
      return message;
    }
    case 5:
      return MeasurementResponse{
          u16(rng, 0, kMaxAdc),
          {u16(rng, 0, kMaxAdc), u16(rng, 0, kMaxAdc), u16(rng, 0, kMaxAdc)},
          u16(rng, 0, kMaxAdc),
          u16(rng, 0, kMaxAdc),
          bit(rng) ? TiltChannel::kRear : TiltChannel::kFront};
    case 6: return DeadManRequest{u8(rng)};
    default: return DeadManResponse{};
  }
}

}  // namespace marsokhod::protocol::test
