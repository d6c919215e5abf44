// A classic CAN 2.0A data frame as it crosses the bus: 11-bit identifier, 0–8 data bytes.
#pragma once

#include <array>
#include <cstdint>

namespace marsokhod::protocol {

struct CanFrame {
  std::uint32_t id = 0;  // 11-bit standard identifier
  std::uint8_t dlc = 0;  // 0..8
  std::array<std::uint8_t, 8> data{};

  friend bool operator==(const CanFrame&, const CanFrame&) = default;
};

}  // namespace marsokhod::protocol
