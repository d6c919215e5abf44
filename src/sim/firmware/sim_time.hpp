// Simulated time of the controllers and the bus: integer nanoseconds since power-on.
//
// Every clock in this layer is an exact multiple of 0.5 µs (tim at 2 MHz/(con+1), one CAN bit at
// 1 Mbit/s = 1 µs, µ8's dead man's timer at 16 MHz/64 = 4 µs per tick), so integers keep event
// times exact: the dead man's switch fires at exactly last_0x80 + dog·262 144 000 ns.
#pragma once

#include <cmath>
#include <cstdint>

namespace marsokhod::sim {

using SimTimeNs = std::int64_t;

inline constexpr SimTimeNs kNanosecondsPerSecond = 1'000'000'000;

// Rounds to the nearest nanosecond (0.001 s → 1 000 000 ns exactly).
inline SimTimeNs seconds_to_ns(double seconds) { return std::llround(seconds * 1e9); }
inline double ns_to_seconds(SimTimeNs time_ns) { return static_cast<double>(time_ns) * 1e-9; }

}  // namespace marsokhod::sim
