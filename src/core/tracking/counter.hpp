// The 16-bit counters of µ0–µ7 (tim, enc, stp, chapter 3.2) wrap at 65536; differences between
// two readings are taken modulo 65536.
#pragma once

#include <cstdint>

namespace marsokhod::tracking {

inline constexpr std::uint32_t kCounterModulus = 65536;

// (later − earlier) mod 65536, in 0..65535.
constexpr std::uint32_t counter_difference(std::uint16_t later, std::uint16_t earlier) {
  // Unsigned arithmetic is modulo 2^32 and 2^16 divides it, so the mask gives the mod-65536 value.
  return (static_cast<std::uint32_t>(later) - static_cast<std::uint32_t>(earlier)) &
         (kCounterModulus - 1);
}

}  // namespace marsokhod::tracking
