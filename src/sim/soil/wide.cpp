#include "sim/soil/wide.hpp"

#include <atomic>
#include <cstdint>
#include <cstring>

#include "sim/soil/fast_math.hpp"

namespace marsokhod::sim::soil::wide {

namespace {
std::atomic<bool> wanted{true};
}  // namespace

void use(bool wide) { wanted.store(wide, std::memory_order_relaxed); }

#if defined(__x86_64__) && defined(__GNUC__)

bool available() {
  static const bool avx2 = __builtin_cpu_supports("avx2") != 0;
  return avx2 && wanted.load(std::memory_order_relaxed);
}

// Everything below is compiled for AVX2 and called only when available(). Nothing from a header
// is instantiated under it (not even std::bit_cast: the builtin instead), so that no function
// compiled for AVX2 can stand in for a header's inline one elsewhere: its helpers are its own.
#pragma GCC push_options
#pragma GCC target("avx2")

namespace {

using Quad = double __attribute__((vector_size(32)));
using BitsQuad = std::uint64_t __attribute__((vector_size(32)));

Quad load(const double* from) {
  Quad value;
  std::memcpy(&value, from, sizeof value);
  return value;
}
void store(double* to, Quad value) { std::memcpy(to, &value, sizeof value); }
Quad splat(double value) { return Quad{value, value, value, value}; }

// detail::exp_nonpositive_lanes, lane by lane the same operations.
Quad exp_nonpositive(Quad x) {
  using namespace detail;
  const Quad floor = splat(kExpNonPositiveFloor);
  x = x < floor ? floor : x;
  const Quad shifted = x * kStepsPerUnit + kRoundBiased;
  const Quad k = shifted - kRoundBiased;
  const Quad r = (x - k * kStepHigh) - k * kStepLow;
  const BitsQuad biased = __builtin_bit_cast(BitsQuad, shifted) - kRoundBits;
  const Quad power = __builtin_bit_cast(Quad, BitsQuad((biased >> 5) << 52));
  const Quad r2 = r * r;
  const Quad high = (1.0 / 24.0 + r * (1.0 / 120.0)) + r2 * (1.0 / 720.0);
  const Quad polynomial = 1.0 + r + r2 * ((0.5 + r * (1.0 / 6.0)) + r2 * high);
  const Quad fractions = {kExp2Fractions[biased[0] & 31], kExp2Fractions[biased[1] & 31],
                          kExp2Fractions[biased[2] & 31], kExp2Fractions[biased[3] & 31]};
  return polynomial * (fractions * power);
}

// detail::mobilised for a pair, four lanes.
Quad mobilised(Quad displacement_m, double inverse_shear_modulus_per_m) {
  const Quad magnitude = displacement_m < 0.0 ? -displacement_m : displacement_m;
  const Quad share = 1.0 - exp_nonpositive(-magnitude * inverse_shear_modulus_per_m);
  return displacement_m < 0.0 ? -share : share;
}

}  // namespace

int blade_shares(const double* jt, const double* jy, int count, double across_t, double across_y,
                 double along_t, double along_y, double inverse_shear_modulus_per_m,
                 double* across, double* along) {
  int k = 0;
  for (; k + 3 < count; k += 4) {
    const Quad t = load(jt + k), y = load(jy + k);
    store(across + k, mobilised(t * across_t + y * across_y, inverse_shear_modulus_per_m));
    store(along + k, mobilised(t * along_t + y * along_y, inverse_shear_modulus_per_m));
  }
  return k;
}

#pragma GCC pop_options

#else

bool available() { return false; }
int blade_shares(const double*, const double*, int, double, double, double, double, double,
                 double*, double*) {
  return 0;
}

#endif

}  // namespace marsokhod::sim::soil::wide
