#include "core/adaptation/load_torque.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "adaptation_test_util.hpp"

namespace marsokhod::adaptation {
namespace {

using test::invalid_argument_message;
using test::kInf;
using test::kNaN;
using ::testing::HasSubstr;

constexpr double kTolerance = 1e-12;

// (4.7) with Procedure 4.13's peak torque 5.51 N m at d = 0.3:
//   τ d ≥ 0: l = 5.51 · 0.030 = 0.1653 rad/s      τ d < 0: l = −5.51 · 0.015 = −0.08265 rad/s
TEST(LoadFromTorque, Procedure4_13PeakTorque) {
  const LoadParams load;
  EXPECT_NEAR(load_from_torque(5.51, 0.3, load), 0.1653, kTolerance);
  EXPECT_NEAR(load_from_torque(-5.51, 0.3, load), -0.08265, kTolerance);
}

// Procedure 4.14's ±2.98 N m while driving backwards, d = −0.5:
//   τ = −2.98: τ d ≥ 0, l = −2.98 · 0.030 = −0.0894;   τ = 2.98: l = 2.98 · 0.015 = 0.0447
TEST(LoadFromTorque, DrivingBackwards) {
  const LoadParams load;
  EXPECT_NEAR(load_from_torque(-2.98, -0.5, load), -0.0894, kTolerance);
  EXPECT_NEAR(load_from_torque(2.98, -0.5, load), 0.0447, kTolerance);
}

// d = 0 makes τ d = 0 ≥ 0, so B⁺ applies in both directions; no torque, no load.
TEST(LoadFromTorque, StandingMotorUsesTheSameSignGain) {
  const LoadParams load;
  EXPECT_NEAR(load_from_torque(1.0, 0.0, load), 0.030, kTolerance);
  EXPECT_NEAR(load_from_torque(-1.0, 0.0, load), -0.030, kTolerance);
  EXPECT_EQ(load_from_torque(0.0, -0.7, load), 0.0);
}

TEST(TorqueFromLoad, InvertsTheHandWorkedValues) {
  const LoadParams load;
  EXPECT_NEAR(torque_from_load(0.1653, 0.3, load), 5.51, kTolerance);
  EXPECT_NEAR(torque_from_load(-0.08265, 0.3, load), -5.51, kTolerance);
  EXPECT_NEAR(torque_from_load(-0.0894, -0.5, load), -2.98, kTolerance);
  EXPECT_NEAR(torque_from_load(0.0447, -0.5, load), 2.98, kTolerance);
  EXPECT_EQ(torque_from_load(0.0, 0.5, load), 0.0);
}

TEST(LoadTorque, RoundTripsOverAGridWithTheSameSign) {
  const LoadParams load;
  for (int t = -100; t <= 100; ++t) {
    for (int d = -20; d <= 20; ++d) {
      const double torque_nm = t / 10.0;
      const double duty = d / 20.0;
      const double load_radps = load_from_torque(torque_nm, duty, load);
      ASSERT_EQ(std::signbit(load_radps), std::signbit(torque_nm)) << torque_nm << ", " << duty;
      ASSERT_NEAR(torque_from_load(load_radps, duty, load), torque_nm, kTolerance)
          << torque_nm << ", " << duty;
    }
  }
}

TEST(LoadTorque, RejectsInvalidInputsByName) {
  const LoadParams load;
  EXPECT_THAT(invalid_argument_message([&] { load_from_torque(kNaN, 0.3, load); }),
              HasSubstr("load_from_torque: torque_nm = nan"));
  EXPECT_THAT(invalid_argument_message([&] { torque_from_load(kInf, 0.3, load); }),
              HasSubstr("torque_from_load: load_radps = inf"));
  EXPECT_THAT(invalid_argument_message([&] { load_from_torque(1.0, 1.5, load); }),
              HasSubstr("duty = 1.5"));
  LoadParams broken;
  broken.gain_opposite_sign_radps_per_nm = 0.0;
  EXPECT_THAT(invalid_argument_message([&] { torque_from_load(1.0, 0.3, broken); }),
              HasSubstr("load.gain_opposite_sign_radps_per_nm = 0"));
  EXPECT_THAT(invalid_argument_message([&] {
                load_from_torque(1e308, 0.3, LoadParams{1e10, 1.0});
              }),
              HasSubstr("overflowed"));
}

// (4.6) with the configured tables (params.hpp): at icr = 511, B⁺ = 0.045 at d = 0 falling
// linearly to (4.7)'s 0.030 at d = 0.3 and constant above; B⁻ half of that.
const LoadGainParams& table_511() {
  static const Params params;
  return select_load_gains(params.load_gains, 511);
}

TEST(LoadGains, TableOfIcr511) {
  EXPECT_NEAR(gains_at(table_511(), 0.0).gain_same_sign_radps_per_nm, 0.045, kTolerance);
  // d = 0.15, half way: (0.045 + 0.030)/2 = 0.0375 and (0.0225 + 0.015)/2 = 0.01875.
  const LoadParams half = gains_at(table_511(), 0.15);
  EXPECT_NEAR(half.gain_same_sign_radps_per_nm, 0.0375, kTolerance);
  EXPECT_NEAR(half.gain_opposite_sign_radps_per_nm, 0.01875, kTolerance);
  // Even in d, and (4.7)'s constants from d = 0.3 on.
  EXPECT_NEAR(gains_at(table_511(), -0.15).gain_same_sign_radps_per_nm, 0.0375, kTolerance);
  for (double d : {0.3, 0.45, 0.6, -0.8, 1.0}) {
    EXPECT_NEAR(gains_at(table_511(), d).gain_same_sign_radps_per_nm, 0.030, kTolerance) << d;
    EXPECT_NEAR(gains_at(table_511(), d).gain_opposite_sign_radps_per_nm, 0.015, kTolerance) << d;
  }
}

// Procedure 4.13 at icr = 511: the weight's 5.51 N m at the procedure's d ∈ [0.3, 0.6] are
// l = 5.51·0.030 = 0.1653 rad/s (τd ≥ 0) and −5.51·0.015 = −0.08265 rad/s (τd < 0), and back.
// At d = 0.15 the same weight pulls l = 5.51·0.0375 = 0.206625 rad/s.
TEST(TorqueEstimate, Procedure4_13Weight) {
  for (double d : {0.3, 0.45, 0.6}) {
    EXPECT_NEAR(torque_estimate_nm(0.1653, d, table_511()), 5.51, 1e-9) << d;
    EXPECT_NEAR(torque_estimate_nm(-0.08265, d, table_511()), -5.51, 1e-9) << d;
  }
  EXPECT_NEAR(torque_estimate_nm(0.206625, 0.15, table_511()), 5.51, 1e-9);
}

// Procedure 4.14 at icr = 1023: ±2.98 N m; B⁺(0) = 0.030·(1 + 0.5·512/1024) = 0.0375, so a
// standing motor (d = 0, τd = 0 ≥ 0: B⁺) reads l = 2.98·0.0375 = 0.11175 rad/s; at d = 0.6
// l = 2.98·0.030 = 0.0894 and, braking (τ = −2.98), −2.98·0.015 = −0.0447 rad/s. The supply
// voltage is not an input: Procedure 4.14 found none at 16 … 24 V.
TEST(TorqueEstimate, Procedure4_14Weight) {
  const Params params;
  const LoadGainParams& table = select_load_gains(params.load_gains, 1023);
  EXPECT_NEAR(torque_estimate_nm(0.11175, 0.0, table), 2.98, 1e-9);
  EXPECT_NEAR(torque_estimate_nm(-0.11175, 0.0, table), -2.98, 1e-9);
  EXPECT_NEAR(torque_estimate_nm(0.0894, 0.6, table), 2.98, 1e-9);
  EXPECT_NEAR(torque_estimate_nm(-0.0447, 0.6, table), -2.98, 1e-9);
  // The round trip through load_from_torque at every duty.
  for (double d = -1.0; d <= 1.0; d += 0.05) {
    for (double tau : {-5.51, -2.98, 0.0, 2.98, 5.51}) {
      const double l = load_from_torque(tau, d, gains_at(table, d));
      EXPECT_NEAR(torque_estimate_nm(l, d, table), tau, 1e-9) << d << " " << tau;
    }
  }
}

TEST(TorqueEstimate, NotFiniteLoadGivesNaNBadTablesAreRejected) {
  EXPECT_TRUE(std::isnan(torque_estimate_nm(kNaN, 0.3, table_511())));
  EXPECT_THAT(invalid_argument_message([] { select_load_gains(Params{}.load_gains, 300); }),
              HasSubstr("no [[load_gain]] table for icr 300 (tables for: 255, 511, 1023, 2047)"));
  LoadGainParams ragged{511, {0.0, 1.0}, {0.03}, {0.015, 0.015}};
  EXPECT_THAT(invalid_argument_message([&] { gains_at(ragged, 0.5); }),
              HasSubstr("as many B⁺ and B⁻ values as duty cycles"));
  EXPECT_THAT(invalid_argument_message([] { gains_at(table_511(), 1.5); }), HasSubstr("1.5"));
}

}  // namespace
}  // namespace marsokhod::adaptation
