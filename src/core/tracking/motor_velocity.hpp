// (3.3) the instantaneous angular velocity w̄ of one motor shaft from vel and dir.
//
// vel is the number of encoder pulses in the last velocity period T(con) = (con+1)·65536/2 MHz,
// so with N = 115000 pulses per revolution
//   w̄^k = (−1)^dir^k · 2π·2e6/(N·65536·(con+1)) · vel = (−1)^dir^k · 25π/(47104(con+1)) · vel
// [rad/s]                                                                                 (3.3)
// positive counter-clockwise around x2. At the no-load speed w = 2.827 rad/s, vel reaches
// ⌈1727.27(con+1)⌉; vel = 1727 at con = 0 is 2.880 rad/s.
#pragma once

#include <cstdint>

namespace marsokhod::tracking {

inline constexpr std::uint16_t kVelocityMaxCounts = 0x7FFF;  // vel is a 15-bit register

// Throws std::invalid_argument if vel exceeds 15 bits (the codec never produces that).
void require_velocity_counts(std::uint16_t vel);

// 2π·2e6/(N·65536·(con+1)) [rad/s per pulse counted in one period T(con)]; 25π/(47104(con+1))
// for N = 115000. Throws std::invalid_argument if con ∉ 0..255 or N ≤ 0.
double velocity_radps_per_count(int con, int encoder_pulses_per_rev);

// (3.3). Throws std::invalid_argument if vel exceeds 15 bits, con ∉ 0..255 or N ≤ 0.
double motor_velocity_radps(std::uint16_t vel, bool dir, int con, int encoder_pulses_per_rev);

}  // namespace marsokhod::tracking
