#include "sim/soil/wide.hpp"

#include <atomic>
#include <cstdint>
#include <cstring>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

#include "sim/soil/fast_math.hpp"
#include "sim/soil/soil_grid.hpp"

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

// The tables the gathers read, as plain pointers taken here, outside the AVX2 region (the log's
// pairs one after the other: 1/c_i at 2i, ln c_i at 2i + 1).
static_assert(sizeof(detail::kLogDivisors) == 64 * sizeof(double), "the pairs one after the other");
const double* const kExpTable = detail::kExp2Fractions.data();
const double* const kLogTable = reinterpret_cast<const double*>(detail::kLogDivisors.data());

// Everything below is compiled for AVX2 and called only when available(). Nothing from a header
// is instantiated or called under it (not even std::bit_cast or std::array's members: builtins
// and the pointers above instead), so that no function compiled for AVX2 can stand in for a
// header's inline one elsewhere: its helpers are its own. (The intrinsics of <immintrin.h> carry
// their own target.)
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2")
#endif

namespace {

using Quad = double __attribute__((vector_size(32)));
using BitsQuad = std::uint64_t __attribute__((vector_size(32)));
using LowQuad = std::int32_t __attribute__((vector_size(16)));  // four cell indices

Quad load(const double* from) {
  Quad value;
  std::memcpy(&value, from, sizeof value);
  return value;
}
void store(double* to, Quad value) { std::memcpy(to, &value, sizeof value); }
Quad splat(double value) { return Quad{value, value, value, value}; }
// table[index[j]] in each lane j, with one AVX2 gather.
Quad gather(const double* table, BitsQuad index) {
  return _mm256_i64gather_pd(table, __builtin_bit_cast(__m256i, index), 8);
}

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
  const Quad fractions = gather(kExpTable, biased & 31);
  return polynomial * (fractions * power);
}

// detail::log_positive_lanes, lane by lane the same operations.
Quad log_positive(Quad x) {
  using namespace detail;
  const BitsQuad bits = __builtin_bit_cast(BitsQuad, x);
  const BitsQuad index = (bits >> 47) & 31;
  const Quad m = __builtin_bit_cast(Quad, BitsQuad((bits & kFractionBits) | kExponentOne));
  const Quad e = __builtin_bit_cast(Quad, BitsQuad((bits >> 52) | kTwo52Bits)) - kTwo52PlusBias;
  const Quad inverse = gather(kLogTable, 2 * index), logarithm = gather(kLogTable, 2 * index + 1);
  const Quad r = m * inverse - 1.0;
  const Quad r2 = r * r;
  const Quad odd = r + r2 * (r * (1.0 / 3.0) + r2 * (r * (1.0 / 5.0) + r2 * (r * (1.0 / 7.0))));
  const Quad even = r2 * (-0.5 + r2 * (-0.25 + r2 * (-1.0 / 6.0)));
  return (e * kLn2High + logarithm) + (e * kLn2Low + (odd + even));
}

// detail::mobilised for a pair, four lanes.
Quad mobilised(Quad displacement_m, double inverse_shear_modulus_per_m) {
  const Quad magnitude = displacement_m < 0.0 ? -displacement_m : displacement_m;
  const Quad share = 1.0 - exp_nonpositive(-magnitude * inverse_shear_modulus_per_m);
  return displacement_m < 0.0 ? -share : share;
}

// SoilGrid::bilinear's axis(): the coordinate in cells clamped to [0, cells − 1] (std::clamp's
// comparisons), the lower cell its truncation kept below cells − 1, the weight the rest.
Quad cell_axis(Quad coordinate, int cells, LowQuad& low) {
  const Quad top = splat(cells - 1.0);
  const Quad clamped = coordinate < 0.0 ? splat(0.0) : (top < coordinate ? top : coordinate);
  low = __builtin_convertvector(clamped, LowQuad);
  const LowQuad highest = {cells - 2, cells - 2, cells - 2, cells - 2};
  low = low < highest ? low : highest;
  return clamped - __builtin_convertvector(low, Quad);
}

// Four cells' levels as bilinear's at() reads them with nothing added: level + 0.0.
Quad gather(const double* levels, LowQuad index) {
  // (The masked form: GCC 12 warns of the plain one's undefined start.)
  const __m256d all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
  return _mm256_mask_i32gather_pd(_mm256_setzero_pd(), levels, __builtin_bit_cast(__m128i, index),
                                  all, 8) +
         0.0;
}

// sheared()'s test for the loading branch (wheel_soil.cpp): the step is 0, or the displacement,
// or they have the same sign.
BitsQuad loading(Quad j, Quad step) {
  const BitsQuad differ =
      __builtin_bit_cast(BitsQuad, j > 0.0) ^ __builtin_bit_cast(BitsQuad, step > 0.0);
  return __builtin_bit_cast(BitsQuad, step == 0.0) | __builtin_bit_cast(BitsQuad, j == 0.0) |
         ~differ;
}

bool all(BitsQuad mask) { return (mask[0] & mask[1] & mask[2] & mask[3]) != 0; }

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

void rim_clearances(const GridSpec& grid, const double* levels_m, const double* axis,
                    const double* side, const double* up, double radius_m, double bottom_m,
                    double touch_m, const double* sines, const double* cosines,
                    double* clearances_m) {
  const Quad along = radius_m * load(sines), down = radius_m * load(cosines);
  const Quad x = (axis[0] + along * side[0]) - down * up[0];
  const Quad y = (axis[1] + along * side[1]) - down * up[1];
  const Quad z = (axis[2] + along * side[2]) - down * up[2];
  LowQuad x0, y0;
  const Quad wx = cell_axis((x - grid.origin_x_m) / grid.cell_m - 0.5, grid.cells_x, x0);
  const Quad wy = cell_axis((y - grid.origin_y_m) / grid.cell_m - 0.5, grid.cells_y, y0);
  const LowQuad row = {grid.cells_x, grid.cells_x, grid.cells_x, grid.cells_x};
  const LowQuad first = y0 * row + x0;
  const double* levels = levels_m;
  const Quad at00 = gather(levels, first), at10 = gather(levels, first + 1);
  const Quad at01 = gather(levels, first + row), at11 = gather(levels, first + row + 1);
  const Quad level = (1.0 - wy) * ((1.0 - wx) * at00 + wx * at10) +
                     wy * ((1.0 - wx) * at01 + wx * at11);
  store(clearances_m, ((z - level) - bottom_m) - touch_m);
}

int advect_loading(double* jt, double* jy, double* peak, const double* cosines, int samples,
                   int first, int whole, double fraction, double spin_term, double travel_mps,
                   double dt_s, double lateral_step_m, int* unloading, int& unloading_count) {
  int k = samples - 1;
  unloading_count = 0;
  const Quad lateral = splat(lateral_step_m);
  for (; k - 3 >= first; k -= 4) {
    const int low = k - 3, at = low - whole;  // the four samples low … k, read from at − 1 …
    const Quad value_t = (1.0 - fraction) * load(jt + at) + fraction * load(jt + at - 1);
    const Quad value_y = (1.0 - fraction) * load(jy + at) + fraction * load(jy + at - 1);
    const Quad step_t = (spin_term - travel_mps * load(cosines + low)) * dt_s;
    BitsQuad loads_t = loading(value_t, step_t);
    const BitsQuad loads_y = loading(value_y, lateral);
    if (peak != nullptr) {
      const Quad value_p = (1.0 - fraction) * load(peak + at) + fraction * load(peak + at - 1);
      store(peak + low, value_p);
      loads_t &= __builtin_bit_cast(BitsQuad, value_p == 0.0);
    }
    store(jt + low, value_t + step_t);
    store(jy + low, value_y + lateral);
    if (all(loads_t & loads_y)) continue;
    for (int j = 3; j >= 0; --j) {  // the interpolated value kept, its step left to the caller
      if (loads_t[j] == 0) {
        jt[low + j] = value_t[j];
        unloading[unloading_count++] = 2 * (low + j);
      }
      if (loads_y[j] == 0) {
        jy[low + j] = value_y[j];
        unloading[unloading_count++] = 2 * (low + j) + 1;
      }
    }
  }
  return k;
}

void bladed_sums(const BladedSample& sample, const double* sines, const double* cosines,
                 const double* sigmas, const double* across, const double* along, int count,
                 BladedSums& sums) {
  Quad fx = splat(0.0), fy = fx, fz = fx, mx = fx, my = fx, mz = fx;
  const double rs = sample.shear_radius_m;
  for (int k = 0; k + 3 < count; k += 4) {
    const Quad s = load(sines + k), c = load(cosines + k), sigma = load(sigmas + k);
    const Quad strength = sample.cohesion_pa + sigma * sample.tan_friction;
    const Quad across_pa = strength * load(across + k);
    const Quad along_pa = sigma * sample.tan_metal_friction * load(along + k);
    const Quad tangential_pa = across_pa * sample.across_t + along_pa * sample.along_t;
    const Quad lateral_pa = across_pa * sample.across_y + along_pa * sample.along_y;
    const Quad normal = sigma * sample.rim_radius_m * sample.area;
    const Quad tangential = tangential_pa * rs * sample.area;
    const Quad lateral = lateral_pa * rs * sample.area;
    fx += tangential * c - normal * s;
    fz += normal * c + tangential * s;
    fy += lateral;
    my -= tangential * rs;
    mx += lateral * rs * c;
    mz += lateral * rs * s;
  }
  store(sums.fx, fx);
  store(sums.fy, fy);
  store(sums.fz, fz);
  store(sums.mx, mx);
  store(sums.my, my);
  store(sums.mz, mz);
}

int bekker_stresses(double modulus_pa, double cos_entry, double radius_m, double exponent_n,
                    double* values, int count) {
  constexpr double kNormal = 0x1p-1022;  // the smallest normal double: log_positive's domain
  int k = 0;
  for (; k + 3 < count; k += 4) {
    const Quad above = load(values + k) - cos_entry;
    const Quad depth = radius_m * (above < 0.0 ? splat(0.0) : above);
    if (!all(__builtin_bit_cast(BitsQuad, depth >= kNormal))) break;
    const Quad exponent = exponent_n * log_positive(depth);
    if (!all(__builtin_bit_cast(BitsQuad, exponent <= 0.0))) break;
    store(values + k, modulus_pa * exp_nonpositive(exponent));
  }
  return k;
}

#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif

#else

bool available() { return false; }
int blade_shares(const double*, const double*, int, double, double, double, double, double,
                 double*, double*) {
  return 0;
}
int bekker_stresses(double, double, double, double, double*, int) { return 0; }
void rim_clearances(const GridSpec&, const double*, const double*, const double*, const double*,
                    double, double, double, const double*, const double*, double*) {}
void bladed_sums(const BladedSample&, const double*, const double*, const double*, const double*,
                 const double*, int, BladedSums&) {}
int advect_loading(double*, double*, double*, const double*, int samples, int, int, double, double,
                   double, double, double, int*, int& unloading_count) {
  unloading_count = 0;
  return samples - 1;
}

#endif

}  // namespace marsokhod::sim::soil::wide
