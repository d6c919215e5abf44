// exp_nonpositive against std::exp: within 3 units in the last place over its range, exact at 0,
// held at its floor below −708, NaN kept; its pair lane by lane the same bits; sin_cos against
// std::sin and std::cos; the blades' four-wide loop (wide.hpp) gives the two-wide form's bits.
#include "sim/soil/fast_math.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "sim/soil/wheel_stress.hpp"
#include "sim/soil/wide.hpp"

namespace marsokhod::sim::soil {
namespace {

// 2 ulp of a result in [2^e, 2^(e+1)) is 2^(e−51): relative to the result at most 2^−51.
constexpr double kTwoUlpRelative = 4.441e-16;

// How many doubles lie between two positive finite ones.
std::uint64_t ulps_apart(double a, double b) {
  const auto x = std::bit_cast<std::uint64_t>(a), y = std::bit_cast<std::uint64_t>(b);
  return x > y ? x - y : y - x;
}

TEST(FastExp, WithinThreeUnitsInTheLastPlaceOfStdExp) {
  std::mt19937_64 random(14);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uint64_t worst = 0;
  // Uniform over each binade from 2^−30 to 2^9 (the soil's arguments lie within 0…−40), and the
  // whole range down to the floor.
  for (int binade = -30; binade <= 9; ++binade) {
    for (int i = 0; i < 20000; ++i) {
      const double x = -std::ldexp(1.0 + unit(random), binade);
      if (x < kExpNonPositiveFloor) continue;
      worst = std::max(worst, ulps_apart(exp_nonpositive(x), std::exp(x)));
    }
  }
  for (int i = 0; i <= 70800; ++i) {  // every 0.01 from 0 to −708, where the table's index wraps
    const double x = -0.01 * i;
    worst = std::max(worst, ulps_apart(exp_nonpositive(x), std::exp(x)));
  }
  EXPECT_LE(worst, 3u);
  EXPECT_GT(worst, 0u);  // it is not std::exp itself
}

TEST(FastExp, ExactWhereTheReductionIsExact) {
  EXPECT_EQ(exp_nonpositive(0.0), 1.0);
  EXPECT_EQ(exp_nonpositive(-0.0), 1.0);
  // x = −m·ln2 to the double nearest: e^x = 2^−m within the rounding of x itself.
  for (int m = 1; m <= 1000; m += 37) {
    const double x = -m * 0.6931471805599453;
    EXPECT_NEAR(exp_nonpositive(x) / std::ldexp(1.0, -m), 1.0, 1e-13) << m;
  }
}

TEST(FastExp, HeldAtItsFloorAndMonotone) {
  const double floor_value = exp_nonpositive(kExpNonPositiveFloor);
  EXPECT_NEAR(floor_value / std::exp(kExpNonPositiveFloor), 1.0, kTwoUlpRelative);
  EXPECT_EQ(exp_nonpositive(-709.0), floor_value);
  EXPECT_EQ(exp_nonpositive(-1e300), floor_value);
  EXPECT_EQ(exp_nonpositive(-INFINITY), floor_value);
  EXPECT_TRUE(std::isnan(exp_nonpositive(std::nan(""))));  // a bad input is not hidden
  const DoublePair pair = exp_nonpositive(DoublePair{std::nan(""), -1.0});
  EXPECT_TRUE(std::isnan(pair[0]));
  EXPECT_EQ(pair[1], exp_nonpositive(-1.0));
  // 1 − e^x, the mobilised share, is 1 from about −38 on, as with std::exp.
  EXPECT_EQ(1.0 - exp_nonpositive(-38.0), 1.0 - std::exp(-38.0));
  double previous = 1.0;
  for (int i = 1; i <= 200000; ++i) {
    const double value = exp_nonpositive(-1e-4 * i);
    ASSERT_LE(value, previous) << i;
    previous = value;
  }
}

TEST(FastExp, APairGivesTheBitsOfTwoSingles) {
  std::mt19937_64 random(15);
  std::uniform_real_distribution<double> argument(-60.0, 0.0);
  for (int i = 0; i < 100000; ++i) {
    const double a = argument(random), b = i % 7 == 0 ? -1000.0 : argument(random);
    const DoublePair pair = exp_nonpositive(DoublePair{a, b});
    ASSERT_EQ(pair[0], exp_nonpositive(a)) << a;
    ASSERT_EQ(pair[1], exp_nonpositive(b)) << b;
  }
}

TEST(WideLoop, TheBladesSharesAreTheBitsOfTheTwoWideForm) {
  if (!wide::available()) GTEST_SKIP() << "no AVX2 here: the two-wide form does all the work";
  std::mt19937_64 random(18);
  std::uniform_real_distribution<double> displacement(-0.08, 0.08);
  const BladeFrame blade = blade_frame(BladeAxes{true, std::sin(0.24), std::cos(0.24)}, -1);
  for (int trial = 0; trial < 2000; ++trial) {
    const int count = 1 + trial % 30;
    std::vector<double> jt(count), jy(count), across(count, -7.0), along(count, -7.0);
    for (int k = 0; k < count; ++k) {
      jt[k] = k % 11 == 3 ? 0.0 : displacement(random);
      jy[k] = k % 13 == 5 ? -0.0 : (k % 17 == 2 ? 3.0 : 0.1 * displacement(random));
    }
    const int done = wide::blade_shares(jt.data(), jy.data(), count, blade.across_t,
                                        blade.across_y, blade.along_t, blade.along_y, 80.0,
                                        across.data(), along.data());
    ASSERT_EQ(done, count / 4 * 4);
    for (int k = 0; k < done; ++k) {
      const DoublePair shares = detail::mobilised(
          DoublePair{blade.across_displacement_m(jt[k], jy[k]),
                     blade.along_displacement_m(jt[k], jy[k])},
          80.0);
      ASSERT_EQ(std::bit_cast<std::uint64_t>(across[k]), std::bit_cast<std::uint64_t>(shares[0]))
          << k;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(along[k]), std::bit_cast<std::uint64_t>(shares[1]))
          << k;
    }
    for (int k = done; k < count; ++k) ASSERT_EQ(across[k], -7.0) << "past what it did";
  }
}

TEST(FastSinCos, WithinTwoUnitsInTheLastPlaceOfOne) {
  double worst_sin = 0.0, worst_cos = 0.0;
  for (int i = -200000; i <= 200000; ++i) {  // [−π/2, π/2] and a little beyond, to 1.6
    const double x = 1.6 * i / 200000.0;
    const SinCos value = sin_cos(x);
    worst_sin = std::max(worst_sin, std::abs(value.sin - std::sin(x)));
    worst_cos = std::max(worst_cos, std::abs(value.cos - std::cos(x)));
  }
  EXPECT_LE(worst_sin, kTwoUlpRelative);  // values up to 1: absolute
  EXPECT_LE(worst_cos, kTwoUlpRelative);
  EXPECT_EQ(sin_cos(0.0).sin, 0.0);
  EXPECT_EQ(sin_cos(0.0).cos, 1.0);
  EXPECT_EQ(sin_cos(-0.3).sin, -sin_cos(0.3).sin);  // odd and even, exactly
  EXPECT_EQ(sin_cos(-0.3).cos, sin_cos(0.3).cos);
}

TEST(FastSinCos, BeyondThePolynomialItIsStdSinAndCos) {
  for (const double x : {1.7, -2.0, 3.0, 100.0}) {
    EXPECT_EQ(sin_cos(x).sin, std::sin(x)) << x;
    EXPECT_EQ(sin_cos(x).cos, std::cos(x)) << x;
  }
}

}  // namespace
}  // namespace marsokhod::sim::soil
