// Inline exponentials, sines and cosines for the soil's hot loops, where glibc's calls (errno
// wrapper and dispatch included) took a quarter of the soft soil's step.
//
// exp_nonpositive: e^x for x ≤ 0 — per arc sample the blades' two mobilised shares
// 1 − e^(−|j|/K) and Bekker's power as e^(n ln x), 1300 exponentials a step for six wheels.
// x = (32·m + i)·ln2/32 + r, |r| ≤ ln2/64 (Cody–Waite: ln2/32 split in two, the high part with
// 32 significant bits so that k·high is exact for |k| < 2^21); e^x = 2^m · 2^(i/32) · e^r, the 32
// values 2^(i/32) correctly rounded (written out below), e^r by its Taylor polynomial of degree 6
// (truncation ≤ 3.5e-18 relative). Within 3 units in the last place of std::exp over [−708, 0]
// (tested); e^0 = 1 exactly; below −708 the result is e^−708 (≈ 3e-308: 1 − e^x is 1 there, as it
// is from about −38 on); a NaN gives NaN; x > 0 is outside its domain (wrong results, no undefined
// behaviour). Plain arithmetic in a fixed order: as repeatable as std::exp. A pair of
// exponentials, one template body for both, costs about what one does: the blades' two shares of
// a sample go together.
//
// sin_cos: sin x and cos x together for |x| ≤ π/2 (every angle of a contact arc, and its steps),
// by their Taylor polynomials, x·(1 − x²/3! + … ) to x²³ and 1 − x²/2! + … to x²² (truncation
// under 2e-18 at π/2), evaluated as one pair; within 4.4e-16 (2 units in the last place of 1) of
// std::sin and std::cos there. Beyond 1.6 it calls them.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

namespace marsokhod::sim::soil {

namespace detail {

inline constexpr std::array<double, 32> kExp2Fractions = {
    0x1.0000000000000p+0,  // 2^(0/32)
    0x1.059b0d3158574p+0,  // 2^(1/32)
    0x1.0b5586cf9890fp+0,  // 2^(2/32)
    0x1.11301d0125b51p+0,  // 2^(3/32)
    0x1.172b83c7d517bp+0,  // 2^(4/32)
    0x1.1d4873168b9aap+0,  // 2^(5/32)
    0x1.2387a6e756238p+0,  // 2^(6/32)
    0x1.29e9df51fdee1p+0,  // 2^(7/32)
    0x1.306fe0a31b715p+0,  // 2^(8/32)
    0x1.371a7373aa9cbp+0,  // 2^(9/32)
    0x1.3dea64c123422p+0,  // 2^(10/32)
    0x1.44e086061892dp+0,  // 2^(11/32)
    0x1.4bfdad5362a27p+0,  // 2^(12/32)
    0x1.5342b569d4f82p+0,  // 2^(13/32)
    0x1.5ab07dd485429p+0,  // 2^(14/32)
    0x1.6247eb03a5585p+0,  // 2^(15/32)
    0x1.6a09e667f3bcdp+0,  // 2^(16/32)
    0x1.71f75e8ec5f74p+0,  // 2^(17/32)
    0x1.7a11473eb0187p+0,  // 2^(18/32)
    0x1.82589994cce13p+0,  // 2^(19/32)
    0x1.8ace5422aa0dbp+0,  // 2^(20/32)
    0x1.93737b0cdc5e5p+0,  // 2^(21/32)
    0x1.9c49182a3f090p+0,  // 2^(22/32)
    0x1.a5503b23e255dp+0,  // 2^(23/32)
    0x1.ae89f995ad3adp+0,  // 2^(24/32)
    0x1.b7f76f2fb5e47p+0,  // 2^(25/32)
    0x1.c199bdd85529cp+0,  // 2^(26/32)
    0x1.cb720dcef9069p+0,  // 2^(27/32)
    0x1.d5818dcfba487p+0,  // 2^(28/32)
    0x1.dfc97337b9b5fp+0,  // 2^(29/32)
    0x1.ea4afa2a490dap+0,  // 2^(30/32)
    0x1.f50765b6e4540p+0,  // 2^(31/32)
};

}  // namespace detail

inline constexpr double kExpNonPositiveFloor = -708.0;

// Two at once (GCC's vector extension: an SSE2 register on x86-64, NEON on ARM), lane by lane
// the same operations, in the same order, as the scalar below, so the same bits.
using DoublePair = double __attribute__((vector_size(16)));

namespace detail {

using BitsPair = std::uint64_t __attribute__((vector_size(16)));

inline constexpr double kStepsPerUnit = 46.16624130844683;  // 32 / ln 2
// Adding 1.5·2^52 + 32·1023 rounds to an integer k + 32·1023 held in the low bits: those bits less
// 1.5·2^52's are k + 32·1023 ≥ 0 (k ≥ −32686 above the floor), whose low 5 bits index the table
// and the rest are m + 1023, 2^m's biased exponent.
inline constexpr double kRoundBiased = 6755399441055744.0 + 32736.0;
inline constexpr std::uint64_t kRoundBits = 0x4338000000000000;  // 1.5·2^52
inline constexpr double kStepHigh = 0.02166084938653512;    // ln2/32, its leading 32 bits
inline constexpr double kStepLow = 5.9631716539705866e-12;  // and the rest

template <class Value>
inline Value exp_reduced_polynomial(Value r) {
  const Value r2 = r * r;
  const Value high = (1.0 / 24.0 + r * (1.0 / 120.0)) + r2 * (1.0 / 720.0);  // r⁴… terms
  return 1.0 + r + r2 * ((0.5 + r * (1.0 / 6.0)) + r2 * high);
}

// What differs between one value and a pair: the integer type of the same width, a constant of
// the value's type, and the table's lookup (one index, or one per lane).
template <class Value>
struct ExpLanes;
template <>
struct ExpLanes<double> {
  using Bits = std::uint64_t;
  static double splat(double value) { return value; }
  static double fractions(Bits index) { return kExp2Fractions[index & 31]; }
};
template <>
struct ExpLanes<DoublePair> {
  using Bits = BitsPair;
  static DoublePair splat(double value) { return DoublePair{value, value}; }
  static DoublePair fractions(Bits index) {
    return DoublePair{kExp2Fractions[index[0] & 31], kExp2Fractions[index[1] & 31]};
  }
};

// The one body of both: the same operations in the same order, lane by lane.
template <class Value>
inline Value exp_nonpositive_lanes(Value x) {
  using Lanes = ExpLanes<Value>;
  using Bits = typename Lanes::Bits;
  const Value floor = Lanes::splat(kExpNonPositiveFloor);
  x = x < floor ? floor : x;  // a NaN stays NaN (its bits index the table harmlessly)
  const Value shifted = x * kStepsPerUnit + kRoundBiased;
  const Value k = shifted - kRoundBiased;
  const Value r = (x - k * kStepHigh) - k * kStepLow;
  const Bits biased = std::bit_cast<Bits>(shifted) - kRoundBits;
  const Value power = std::bit_cast<Value>(Bits((biased >> 5) << 52));  // 2^m, m = ⌊k/32⌋
  return exp_reduced_polynomial(r) * (Lanes::fractions(biased) * power);
}

}  // namespace detail

inline double exp_nonpositive(double x) { return detail::exp_nonpositive_lanes(x); }
inline DoublePair exp_nonpositive(DoublePair x) { return detail::exp_nonpositive_lanes(x); }

namespace detail {

// Per power of x², the Taylor coefficients of sin x / x and of cos x: (−1)^k/(2k+1)!, (−1)^k/(2k)!.
inline constexpr std::array<DoublePair, 12> kSinCosTaylor = {{
    {1.0, 1.0},
    {-0.16666666666666666, -0.5},
    {0.008333333333333333, 0.041666666666666664},
    {-0.0001984126984126984, -0.001388888888888889},
    {2.7557319223985893e-06, 2.48015873015873e-05},
    {-2.505210838544172e-08, -2.755731922398589e-07},
    {1.6059043836821613e-10, 2.08767569878681e-09},
    {-7.647163731819816e-13, -1.1470745597729725e-11},
    {2.8114572543455206e-15, 4.779477332387385e-14},
    {-8.22063524662433e-18, -1.5619206968586225e-16},
    {1.9572941063391263e-20, 4.110317623312165e-19},
    {-3.868170170630684e-23, -8.896791392450574e-22},
}};

inline constexpr double kSinCosPolynomialLimit = 1.6;

}  // namespace detail

struct SinCos {
  double sin = 0.0, cos = 1.0;
};

inline SinCos sin_cos(double x) {
  using namespace detail;
  if (!(std::abs(x) <= kSinCosPolynomialLimit)) return {std::sin(x), std::cos(x)};
  const double x2 = x * x;
  DoublePair sum = kSinCosTaylor[11];
  for (int k = 10; k >= 0; --k) sum = sum * x2 + kSinCosTaylor[static_cast<std::size_t>(k)];
  return {x * sum[0], sum[1]};
}

}  // namespace marsokhod::sim::soil
