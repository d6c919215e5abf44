// exp_nonpositive against std::exp: within 3 units in the last place over its range, exact at 0,
// held at its floor below −708, NaN kept; its pair lane by lane the same bits; log_positive
// against std::log (absolutely near 1, in units in the last place beyond), its pair lane by lane
// the same bits; sin_cos against std::sin and std::cos; the four-wide loops (wide.hpp) give the
// bits of the forms they stand in for, worked out here one by one.
#include "sim/soil/fast_math.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "sim/soil/soil_grid.hpp"
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

TEST(FastLog, WithinItsBoundsOfStdLogOverEveryBinade) {
  std::mt19937_64 random(16);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uint64_t worst_ulps = 0;
  double worst_absolute = 0.0;
  const auto compare = [&](double x) {
    const double exact = std::log(x), value = log_positive(x);
    if (std::abs(exact) >= 0.5) {
      worst_ulps = std::max(worst_ulps, ulps_apart(std::abs(value), std::abs(exact)));
    } else {
      worst_absolute = std::max(worst_absolute, std::abs(value - exact));
    }
  };
  // Every binade of the normal doubles (the depths lie within 2^−30…2^−2 m), uniform within each,
  // and every step of 2^−12 over [½, 2], where the result nears 0.
  for (int binade = -1022; binade <= 1023; ++binade) {
    for (int i = 0; i < 400; ++i) compare(std::ldexp(1.0 + unit(random), binade));
  }
  for (int i = 2048; i <= 8192; ++i) compare(std::ldexp(static_cast<double>(i), -12));
  EXPECT_LE(worst_ulps, 4u);
  EXPECT_GT(worst_ulps, 0u);  // it is not std::log itself
  // The polynomial's truncation, (1/65)^8/8 = 3.9e-16, and the rounding of its sum: 4.7e-16 is
  // met near 1.031, the top of the first cell (i = 0), where r reaches 1/65.
  EXPECT_LE(worst_absolute, 5e-16);
  EXPECT_EQ(log_positive(std::numeric_limits<double>::min()),
            std::log(std::numeric_limits<double>::min()));  // −1022·ln 2, exactly rounded
}

TEST(FastLog, APairGivesTheBitsOfTwoSingles) {
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> exponent(-60.0, 5.0);
  for (int i = 0; i < 100000; ++i) {
    const double a = std::exp2(exponent(random)), b = std::exp2(exponent(random));
    const DoublePair pair = log_positive(DoublePair{a, b});
    ASSERT_EQ(std::bit_cast<std::uint64_t>(pair[0]), std::bit_cast<std::uint64_t>(log_positive(a)));
    ASSERT_EQ(std::bit_cast<std::uint64_t>(pair[1]), std::bit_cast<std::uint64_t>(log_positive(b)));
  }
}

TEST(WideLoop, BekkersPowersAreTheBitsOfOneByOne) {
  if (!wide::available()) GTEST_SKIP() << "no AVX2 here: the two-wide form does all the work";
  std::mt19937_64 random(19);
  std::uniform_real_distribution<double> angle(0.0, 0.6), exponent(0.5, 1.6);
  for (int trial = 0; trial < 2000; ++trial) {
    ContactArc arc;
    arc.entry_rad = 0.6;
    arc.cos_entry = std::cos(arc.entry_rad);
    arc.sinkage_exponent = exponent(random);
    const int count = 24;
    std::vector<double> cosines(count);
    for (double& value : cosines) value = std::cos(angle(random));
    if (trial % 5 == 0) cosines[count - 3] = arc.cos_entry;  // a depth of 0: the quad is left
    std::vector<double> values = cosines;
    const int done = wide::bekker_stresses(2.0e6, arc.cos_entry, 0.115, arc.sinkage_exponent,
                                           values.data(), count);
    ASSERT_EQ(done, trial % 5 == 0 ? 20 : 24);
    for (int k = 0; k < done; ++k) {
      const double one = normal_stress_from_cos_pa(2.0e6, arc, 0.115, cosines[k]);
      ASSERT_EQ(std::bit_cast<std::uint64_t>(values[k]), std::bit_cast<std::uint64_t>(one)) << k;
    }
    for (int k = done; k < count; ++k) EXPECT_EQ(values[k], cosines[k]) << "past what it did";
  }
}

// The rim's clearance at four angles against the same points' one-by-one form on a rough grid:
// ((p_z − surface_m(p_x, p_y)) − bottom) − touch, p = axis + (r sin θ)·side − (r cos θ)·up, with
// points inside the grid and beyond its edges (clamped: the weights 0 and 1).
TEST(WideLoop, TheRimsClearancesAreTheBitsOfOneByOne) {
  if (!wide::available()) GTEST_SKIP() << "no AVX2 here: the searches look one by one";
  const GridSpec spec{-0.3, -0.2, 0.02, 30, 20};
  SoilGrid grid(spec, dry_sand(), [](double, double) { return 0.0; });
  std::mt19937_64 random(20);
  std::uniform_real_distribution<double> level(-0.05, 0.05), place(-0.45, 0.45), unit(-1.0, 1.0);
  for (int iy = 0; iy < spec.cells_y; ++iy) {
    for (int ix = 0; ix < spec.cells_x; ++ix) grid.set_cell_surface_m(ix, iy, level(random));
  }
  for (int trial = 0; trial < 20000; ++trial) {
    const Vec3 axis{place(random), place(random), 0.1 + 0.1 * unit(random)};
    const double heading = 3.2 * unit(random);
    const Vec3 side{std::cos(heading), std::sin(heading), 0.2 * unit(random)};
    const Vec3 up{0.1 * unit(random), 0.1 * unit(random), 1.0};
    const double bottom = trial % 3 == 0 ? 0.0 : 0.01 * std::abs(unit(random));
    const double touch = 8.7e-4;
    std::array<double, 4> sines{}, cosines{}, clearances{};
    for (std::size_t j = 0; j < 4; ++j) {
      const double theta = 0.7 * unit(random);
      sines[j] = std::sin(theta);
      cosines[j] = std::cos(theta);
    }
    if (trial % 7 == 0) {  // θ = 0 in every lane: the rim's bottom four times, the same bits
      sines = {0.0, 0.0, 0.0, 0.0};
      cosines = {1.0, 1.0, 1.0, 1.0};
    }
    wide::rim_clearances(spec, grid.cell_surfaces_m(), axis.data(), side.data(), up.data(), 0.115,
                         bottom, touch, sines.data(), cosines.data(), clearances.data());
    for (std::size_t j = 0; j < 4; ++j) {
      const Vec3 rim = axis + (0.115 * sines[j]) * side - (0.115 * cosines[j]) * up;
      const double one = ((rim[2] - grid.surface_m(rim[0], rim[1])) - bottom) - touch;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(clearances[j]), std::bit_cast<std::uint64_t>(one))
          << "trial " << trial << ", lane " << j;
    }
  }
}

// The advection's four-wide loop against its definition (wide.hpp), sample by sample: a loading
// sample takes the interpolated value plus its step, an unloading one keeps the interpolated value
// and is listed for the caller; it reads only values from before the step (in place). With the
// tangential reload memory the peaks move the same way, and a sample with a peak is listed too.
TEST(WideLoop, TheAdvectionIsTheBitsOfOneByOne) {
  if (!wide::available()) GTEST_SKIP() << "no AVX2 here: the advection goes one by one";
  std::mt19937_64 random(21);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const int samples = 24;
  int listed = 0, listed_for_peaks = 0;
  for (int trial = 0; trial < 10000; ++trial) {
    const bool memory = trial % 2 == 1;
    std::vector<double> jt(samples), jy(samples), cosines(samples), peak(samples, 0.0);
    for (int k = 0; k < samples; ++k) {
      jt[k] = k % 9 == 4 ? 0.0 : 0.02 * unit(random) + 0.01;
      jy[k] = k % 7 == 3 ? 0.0 : 0.002 * unit(random);
      cosines[k] = std::cos(0.5 * unit(random));
      if (memory && k % 5 == 2) peak[k] = 0.03 * unit(random);
    }
    // Mostly under a sample a step (whole = 0), sometimes a few, and up to the whole arc.
    const int whole =
        (trial / 2) % 4 != 0 ? 0 : ((trial / 2) % 3 == 0 ? (trial / 8) % samples : 1 + trial % 3);
    const int first = std::min(whole + 1, samples);
    const double fraction = 0.5 * (1.0 + unit(random));
    const double spin_term = trial % 5 == 0 ? 0.0 : 0.2 * unit(random);
    const double travel = 0.1 * unit(random), dt = 1e-3;
    const double lateral = trial % 6 == 0 ? 0.0 : 1e-4 * unit(random);
    const std::vector<double> jt0 = jt, jy0 = jy, peak0 = peak;
    std::vector<int> unloading(2 * samples, -1);
    int count = 0;
    const int last = wide::advect_loading(
        jt.data(), jy.data(), memory ? peak.data() : nullptr, cosines.data(), samples, first,
        whole, fraction, spin_term, travel, dt, lateral, unloading.data(), count);
    ASSERT_EQ((samples - 1 - last) % 4, 0);
    ASSERT_LT(last - 3, first);  // it did every whole group of four
    ASSERT_GE(last, first - 1);
    const auto loads = [](double j, double step) {
      return step == 0.0 || j == 0.0 || (j > 0.0) == (step > 0.0);
    };
    std::vector<int> expected;
    for (int k = samples - 1; k > last; --k) {
      const int at = k - whole;
      const double value_t = (1.0 - fraction) * jt0[at] + fraction * jt0[at - 1];
      const double value_y = (1.0 - fraction) * jy0[at] + fraction * jy0[at - 1];
      const double value_p = (1.0 - fraction) * peak0[at] + fraction * peak0[at - 1];
      const double step_t = (spin_term - travel * cosines[k]) * dt;
      const bool fast_t = loads(value_t, step_t) && (!memory || value_p == 0.0);
      const double t = fast_t ? value_t + step_t : value_t;
      const double y = loads(value_y, lateral) ? value_y + lateral : value_y;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(jt[k]), std::bit_cast<std::uint64_t>(t)) << k;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(jy[k]), std::bit_cast<std::uint64_t>(y)) << k;
      if (memory) {
        ASSERT_EQ(std::bit_cast<std::uint64_t>(peak[k]), std::bit_cast<std::uint64_t>(value_p))
            << k;
        if (loads(value_t, step_t) && value_p != 0.0) ++listed_for_peaks;
      } else {
        ASSERT_EQ(peak[k], 0.0) << "untouched without the memory";
      }
      if (!fast_t) expected.push_back(2 * k);
      if (!loads(value_y, lateral)) expected.push_back(2 * k + 1);
    }
    std::vector<int> got(unloading.begin(), unloading.begin() + count);
    std::sort(got.begin(), got.end());
    std::sort(expected.begin(), expected.end());
    ASSERT_EQ(got, expected);
    listed += count;
    for (int k = 0; k <= last; ++k) {
      ASSERT_EQ(jt[k], jt0[k]) << "past what it did";
      ASSERT_EQ(jy[k], jy0[k]) << "past what it did";
      ASSERT_EQ(peak[k], peak0[k]) << "past what it did";
    }
  }
  EXPECT_GT(listed, 1000);           // the unloading samples were met
  EXPECT_GT(listed_for_peaks, 200);  // and loading ones with a peak
}

// A bladed lane's six sums, four-wide, against the formulas of wide.hpp summed lane by lane.
TEST(WideLoop, TheBladedSumsAreTheBitsOfOneByOne) {
  if (!wide::available()) GTEST_SKIP() << "no AVX2 here: the sums go one by one";
  std::mt19937_64 random(22);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const int count = 1 + trial % 30;
    std::vector<double> s(count), c(count), sigma(count), across(count), along(count);
    for (int k = 0; k < count; ++k) {
      s[k] = 0.6 * unit(random);
      c[k] = std::sqrt(1.0 - s[k] * s[k]);
      sigma[k] = 2e4 * (1.0 + unit(random));
      across[k] = unit(random);
      along[k] = unit(random);
    }
    const wide::BladedSample sample{1040.0, 0.53, 0.35, 0.97, 0.24, -0.24, 0.97, 0.115, 0.125,
                                    0.02 * 0.05};
    wide::BladedSums sums{};
    wide::bladed_sums(sample, s.data(), c.data(), sigma.data(), across.data(), along.data(),
                      count, sums);
    double fx[4] = {}, fy[4] = {}, fz[4] = {}, mx[4] = {}, my[4] = {}, mz[4] = {};
    for (int k = 0; k < count - count % 4; ++k) {
      const int j = k % 4;
      const double strength = sample.cohesion_pa + sigma[k] * sample.tan_friction;
      const double across_pa = strength * across[k];
      const double along_pa = sigma[k] * sample.tan_metal_friction * along[k];
      const double tangential_pa = across_pa * sample.across_t + along_pa * sample.along_t;
      const double lateral_pa = across_pa * sample.across_y + along_pa * sample.along_y;
      const double normal = sigma[k] * sample.rim_radius_m * sample.area;
      const double tangential = tangential_pa * sample.shear_radius_m * sample.area;
      const double lateral = lateral_pa * sample.shear_radius_m * sample.area;
      fx[j] += tangential * c[k] - normal * s[k];
      fz[j] += normal * c[k] + tangential * s[k];
      fy[j] += lateral;
      my[j] -= tangential * sample.shear_radius_m;
      mx[j] += lateral * sample.shear_radius_m * c[k];
      mz[j] += lateral * sample.shear_radius_m * s[k];
    }
    for (int j = 0; j < 4; ++j) {
      const std::array<std::pair<double, double>, 6> pairs = {
          {{sums.fx[j], fx[j]}, {sums.fy[j], fy[j]}, {sums.fz[j], fz[j]},
           {sums.mx[j], mx[j]}, {sums.my[j], my[j]}, {sums.mz[j], mz[j]}}};
      for (const auto& [got, want] : pairs) {
        ASSERT_EQ(std::bit_cast<std::uint64_t>(got), std::bit_cast<std::uint64_t>(want))
            << "trial " << trial << ", lane " << j;
      }
    }
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
