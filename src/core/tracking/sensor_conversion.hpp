// Chapter 3.3: µ8's 10-bit readings (yaw, acc¹⁻³, tltᶠ/tltʳ, vcc) in physical units.
//
//   ω3 = 0.0170·(y − yaw)                                        [rad/s]   (3.4)
//   a_i = g·(acc_i(g) + acc_i(−g) − 2·acc_i)/(acc_i(g) − acc_i(−g))  [m/s²]  (3.5)
//   θf = 0.00495·tltᶠ − 2.61,  θr = −0.00526·tltʳ + 2.74           [rad]  (Procedure 3.4, docs/design.md)
//   U = 0.06768·vcc − 41.0823                                     [V]     (Procedure 3.5)
//
// The accelerometer uses (3.5) with Procedure 3.3's ±g table, not the chapter 3.3 table's affine
// conversions: those are exactly the negation of (3.5) on every axis (gain 2g/(acc(g) − acc(−g)),
// e.g. 0.0732 for x1). At rest on flat ground it shows only on x3, where (3.5) gives −9.81 m/s²
// and the table +9.82. (3.5) is what chapter 6.2.1 feeds, starting from g⁰ = (0, 0, −1).
//
// At the TYP readings (yaw 505, acc 279/251/376, tltᶠ 527, tltʳ 520, vcc 970): ω3 = 0,
// a = (0, 0.0373, −9.81), θf = −0.00135, θr = +0.0048, U = 24.567 V.
#pragma once

#include <cstdint>

#include "core/params.hpp"

namespace marsokhod::tracking {

inline constexpr std::uint16_t kAdcMaxCounts = 1023;  // µ8's analog-to-digital converter: 10 bits

// Throws std::invalid_argument naming the first parameter that is not finite or out of range:
// g > 0, gyro gain > 0, gyro null and ±g readings in 0..1023 with acc(g) ≠ acc(−g), tilt gains
// ≠ 0, supply gain > 0, all offsets finite.
void validate(const SensorParams& params);

// (3.4): the yaw rate around x3 [rad/s] from a reading and the null-rate reading y [counts].
double yaw_rate_radps(double yaw_counts, double gyro_null_counts, double radps_per_count);

// (3.5): the acceleration along one accelerometer axis [m/s²].
double accelerometer_mps2(double acc_counts, const AccelerometerAxisParams& axis,
                          double gravity_mps2);

}  // namespace marsokhod::tracking
