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
// log_positive: ln x for a positive normal x — Bekker's power e^(n ln x) of every arc sample's
// depth, two at a time, without glibc's call and errno wrapper (a third of the normal stresses'
// instructions). x = 2^e · m, m ∈ [1, 2); the five leading bits of m's fraction pick
// c_i = 1 + (i + ½)/32, whose rounded inverse (written out below) leaves r = m/c_i − 1 within
// ±1/65, and ln x = e·ln 2 + ln c_i + ln(1 + r), ln c_i as −ln of the rounded inverse, correctly
// rounded, so that the inverse's rounding cancels; ln(1 + r) by its Taylor polynomial of degree 7
// (truncation ≤ 3.9e-16 at |r| ≤ 1/65). Within 5e-16 absolutely where |ln x| < 1/2 (4.7e-16 met
// near x = 1.031, where r is largest), and 4 units in the last place beyond (tested). Zero,
// negative, subnormal, infinite or NaN x are outside its domain (wrong results, no undefined
// behaviour): the callers take std::log below the smallest normal double.
//
// sin_cos: sin x and cos x together for |x| ≤ π/2 (every angle of a contact arc, and its steps),
// by their Taylor polynomials, x·(1 − x²/3! + … ) to x²³ and 1 − x²/2! + … to x²² (truncation
// under 2e-18 at π/2; fewer terms below ½ and 1/16, truncated as finely), evaluated as one pair;
// within 4.4e-16 (2 units in the last place of 1) of std::sin and std::cos there. Beyond 1.6 it
// calls them.
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

// Per i: 1/c_i rounded, c_i = 1 + (i + ½)/32, and −ln of that rounded inverse, correctly rounded.
inline constexpr std::array<std::array<double, 2>, 32> kLogDivisors = {{
    {0x1.f81f81f81f820p-1, 0x1.fc0a8b0fc03c4p-7},  // i = 0
    {0x1.e9131abf0b767p-1, 0x1.77458f632dcffp-5},  // i = 1
    {0x1.dae6076b981dbp-1, 0x1.341d7961bd1d0p-4},  // i = 2
    {0x1.cd85689039b0bp-1, 0x1.a926d3a4ad562p-4},  // i = 3
    {0x1.c0e070381c0e0p-1, 0x1.0d77e7cd08e5bp-3},  // i = 4
    {0x1.b4e81b4e81b4fp-1, 0x1.44d2b6ccb7d1cp-3},  // i = 5
    {0x1.a98ef606a63bep-1, 0x1.7ab890210d907p-3},  // i = 6
    {0x1.9ec8e951033d9p-1, 0x1.af3c94e80bff3p-3},  // i = 7
    {0x1.948b0fcd6e9e0p-1, 0x1.e27076e2af2e8p-3},  // i = 8
    {0x1.8acb90f6bf3aap-1, 0x1.0a324e27390e2p-2},  // i = 9
    {0x1.8181818181818p-1, 0x1.22941fbcf7966p-2},  // i = 10
    {0x1.78a4c8178a4c8p-1, 0x1.3a64c556945eap-2},  // i = 11
    {0x1.702e05c0b8170p-1, 0x1.51aad872df82ep-2},  // i = 12
    {0x1.6816816816817p-1, 0x1.686c81e9b14adp-2},  // i = 13
    {0x1.6058160581606p-1, 0x1.7eaf83b82afc2p-2},  // i = 14
    {0x1.58ed2308158edp-1, 0x1.947941c2116fbp-2},  // i = 15
    {0x1.51d07eae2f815p-1, 0x1.a9cec9a9a084ap-2},  // i = 16
    {0x1.4afd6a052bf5bp-1, 0x1.beb4d9da71b7ap-2},  // i = 17
    {0x1.446f86562d9fbp-1, 0x1.d32fe7e00ebd5p-2},  // i = 18
    {0x1.3e22cbce4a902p-1, 0x1.e744261d68789p-2},  // i = 19
    {0x1.3813813813814p-1, 0x1.faf588f78f31dp-2},  // i = 20
    {0x1.323e34a2b10bfp-1, 0x1.0723e5c1cdf41p-1},  // i = 21
    {0x1.2c9fb4d812ca0p-1, 0x1.109f39e2d4c96p-1},  // i = 22
    {0x1.27350b8812735p-1, 0x1.19ee6b467c96fp-1},  // i = 23
    {0x1.21fb78121fb78p-1, 0x1.23130d7bebf43p-1},  // i = 24
    {0x1.1cf06ada2811dp-1, 0x1.2c0e9ed448e8cp-1},  // i = 25
    {0x1.1811811811812p-1, 0x1.34e289d9ce1d2p-1},  // i = 26
    {0x1.135c81135c811p-1, 0x1.3d9026a7156fbp-1},  // i = 27
    {0x1.0ecf56be69c90p-1, 0x1.4618bc21c5ec2p-1},  // i = 28
    {0x1.0a6810a6810a7p-1, 0x1.4e7d811b75bb0p-1},  // i = 29
    {0x1.0624dd2f1a9fcp-1, 0x1.56bf9d5b3f399p-1},  // i = 30
    {0x1.0204081020408p-1, 0x1.5ee02a9241676p-1},  // i = 31
}};
// ln 2, its leading 32 bits (so that e·high is exact), and the rest.
inline constexpr double kLn2High = 0x1.62e42fee00000p-1;
inline constexpr double kLn2Low = 0x1.a39ef35793c76p-33;
inline constexpr std::uint64_t kExponentOne = 0x3ff0000000000000;
inline constexpr std::uint64_t kFractionBits = 0x000fffffffffffff;
// 2^52 + the biased exponent, less 2^52 + 1023: the exponent e as a double, without a conversion.
inline constexpr std::uint64_t kTwo52Bits = 0x4330000000000000;
inline constexpr double kTwo52PlusBias = 4503599627371519.0;

template <class Value>
inline Value log1p_reduced_polynomial(Value r) {
  const Value r2 = r * r;
  const Value odd = r + r2 * (r * (1.0 / 3.0) + r2 * (r * (1.0 / 5.0) + r2 * (r * (1.0 / 7.0))));
  const Value even = r2 * (-0.5 + r2 * (-0.25 + r2 * (-1.0 / 6.0)));
  return odd + even;
}

template <class Value>
struct LogLanes;
template <>
struct LogLanes<double> {
  using Bits = std::uint64_t;
  static double inverse(Bits index) { return kLogDivisors[index][0]; }
  static double logarithm(Bits index) { return kLogDivisors[index][1]; }
};
template <>
struct LogLanes<DoublePair> {
  using Bits = BitsPair;
  static DoublePair inverse(Bits index) {
    return DoublePair{kLogDivisors[index[0]][0], kLogDivisors[index[1]][0]};
  }
  static DoublePair logarithm(Bits index) {
    return DoublePair{kLogDivisors[index[0]][1], kLogDivisors[index[1]][1]};
  }
};

// The one body of both, as for the exponential.
template <class Value>
inline Value log_positive_lanes(Value x) {
  using Lanes = LogLanes<Value>;
  using Bits = typename Lanes::Bits;
  const Bits bits = std::bit_cast<Bits>(x);
  const Bits index = (bits >> 47) & 31;
  const Value m = std::bit_cast<Value>(Bits((bits & kFractionBits) | kExponentOne));
  const Value e = std::bit_cast<Value>(Bits((bits >> 52) | kTwo52Bits)) - kTwo52PlusBias;
  const Value r = m * Lanes::inverse(index) - 1.0;
  return (e * kLn2High + Lanes::logarithm(index)) + (e * kLn2Low + log1p_reduced_polynomial(r));
}

}  // namespace detail

inline double log_positive(double x) { return detail::log_positive_lanes(x); }
inline DoublePair log_positive(DoublePair x) { return detail::log_positive_lanes(x); }

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
  const double magnitude = std::abs(x);
  if (!(magnitude <= kSinCosPolynomialLimit)) return {std::sin(x), std::cos(x)};
  // Fewer terms for the small angles most calls take (an arc's steps, a search's angles): to
  // x⁹ and x⁸ within 1/16 (truncation under 3e-19), to x¹⁵ and x¹⁴ within ½ (under 1e-18).
  const int top = magnitude <= 0.0625 ? 4 : (magnitude <= 0.5 ? 7 : 11);
  const double x2 = x * x;
  DoublePair sum = kSinCosTaylor[static_cast<std::size_t>(top)];
  for (int k = top - 1; k >= 0; --k) sum = sum * x2 + kSinCosTaylor[static_cast<std::size_t>(k)];
  return {x * sum[0], sum[1]};
}

}  // namespace marsokhod::sim::soil
