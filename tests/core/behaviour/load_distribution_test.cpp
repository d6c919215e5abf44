#include "core/behaviour/load_distribution.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <random>

#include "behaviour_test_support.hpp"

namespace marsokhod::behaviour {
namespace {

using test::invalid_argument_message;
using test::kNaN;
using ::testing::HasSubstr;

constexpr double kTolerance = 1e-12;
constexpr double kForwardRadps = 1.0;  // v1 > 0

double wheel_sum(const MotorVector& correction) {
  double sum = 0.0;
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    sum += correction[i];
  }
  return sum;
}

MotorVector variance(const MotorVector& loads_radps, double drive_radps = kForwardRadps) {
  return variance_load_distribution_radps(loads_radps, drive_radps, LoadDistributionParams{});
}

MotorVector slip(const MotorVector& loads_radps, double drive_radps = kForwardRadps) {
  return slip_load_distribution_radps(loads_radps, drive_radps, LoadDistributionParams{});
}

// The situations of chapter 6.3, driving forward. l = w − ν: a wheel that carries the rover
// pushes against resistance and runs slower than its no-load speed, l < 0; here −0.2 rad/s.
//
// (a) Wheel 0 spins free (lost grip): l = (0, −0.2 × 5). l̄ = −1/6 = −0.166667,
//     l̄ − l_0 = −0.166667, l̄ − l_j = +0.033333, var = (0.027778 + 5 · 0.001111)/5 = 0.0066667,
//     sqrt = 0.081650.
//   h^v_0 = 5 · (−0.166667) · 0.081650 = −0.068041, h^v_j = 5 · 0.033333 · 0.081650 = +0.013608.
//   (l̄ − l_j) l_j: 0 for wheel 0, 0.033333 · (−0.2) = −0.0066667 for the others; mean
//   −0.0055556. h^s_0 = 5 · (−0.0055556 − 0) = −0.027778, h^s_j = 5 · (−0.0055556 + 0.0066667)
//   = +0.0055556.
//   Both slow the free wheel and speed up the five with grip: power moves to where it pushes.
//   Nothing reaches H = 0.3, so this is the thesis' clip exactly.
TEST(LoadDistribution, SituationA_FreeWheelGivesItsPowerToTheOthers) {
  const MotorVector loads_radps{0.0, -0.2, -0.2, -0.2, -0.2, -0.2, 0.0, 0.0};
  const MotorVector by_variance = variance(loads_radps);
  const MotorVector by_slip = slip(loads_radps);
  EXPECT_NEAR(by_variance[0], -0.068041, 1e-6);
  EXPECT_NEAR(by_slip[0], -0.027778, 1e-6);
  for (std::size_t i = 1; i < kWheelCount; ++i) {
    EXPECT_NEAR(by_variance[i], 0.013608, 1e-6);
    EXPECT_NEAR(by_slip[i], 0.0055556, 1e-6);
  }
}

// (b) Wheel 0 stuck behind an obstacle: l = (−1, −0.2 × 5). l̄ = −0.333333,
//     l̄ − l_0 = 0.666667, l̄ − l_j = −0.133333, var = (0.444444 + 5 · 0.017778)/5 = 0.106667,
//     sqrt = 0.326599.
//   h^v = (5 · 0.666667 · 0.326599, 5 · (−0.133333) · 0.326599) = (1.088662, −0.217732 × 5).
//   (l̄ − l_j) l_j: −0.666667 and +0.026667; mean −0.088889;
//   h^s = (5 · (−0.088889 + 0.666667), 5 · (−0.088889 − 0.026667)) = (2.888889, −0.577778 × 5).
//   Both are in the ratio 1 : −1/5; scaled so the largest is H = 0.3: (0.3, −0.06 × 5). The
//   stuck wheel gets more power to climb, the others yield it. (Element-wise clipping would
//   give (0.3, −0.217732 × 5) with sum −0.788662: not a redistribution.)
TEST(LoadDistribution, SituationB_StuckWheelTakesPowerFromTheOthers) {
  const MotorVector loads_radps{-1.0, -0.2, -0.2, -0.2, -0.2, -0.2, 0.0, 0.0};
  for (const MotorVector& correction : {variance(loads_radps), slip(loads_radps)}) {
    EXPECT_NEAR(correction[0], 0.3, kTolerance);
    for (std::size_t i = 1; i < kWheelCount; ++i) {
      EXPECT_NEAR(correction[i], -0.06, kTolerance);
    }
    EXPECT_NEAR(wheel_sum(correction), 0.0, kTolerance);
  }
}

// (c) Even load: l_i = l̄, every (l̄ − l_i) = 0, so h^v = h^s = 0 (to rounding: 6 · (−0.2)/6
// is not exactly −0.2 in binary).
TEST(LoadDistribution, SituationC_EvenLoadChangesNothing) {
  const MotorVector loads_radps{-0.2, -0.2, -0.2, -0.2, -0.2, -0.2, 0.0, 0.0};
  for (const MotorVector& correction : {variance(loads_radps), slip(loads_radps)}) {
    for (const double value : correction) {
      EXPECT_NEAR(value, 0.0, 1e-15);
    }
  }
}

// Example 6.5: "h^v fails to speed up the wheel with excess velocity". Wheel 0 is dragged
// faster than its motor drives it (l_0 = +0.3 > 0: it brakes the rover), the others push:
// l = (0.3, −0.2 × 5). l̄ = −0.116667, l̄ − l_0 = −0.416667, l̄ − l_j = +0.083333,
// var = (0.173611 + 5 · 0.006944)/5 = 0.041667, sqrt = 0.204124.
//   h^v_0 = 5 · (−0.416667) · 0.204124 = −0.425259: slows the braking wheel further (fails).
//   (l̄ − l_j) l_j: −0.125 and −0.016667; mean −0.034722;
//   h^s_0 = 5 · (−0.034722 + 0.125) = +0.451389, h^s_j = 5 · (−0.034722 + 0.016667)
//   = −0.090278: speeds it up so it stops braking. Both scaled to H = 0.3:
//   h^v = (−0.3, 0.06 × 5), h^s = (0.3, −0.06 × 5).
// The difference is the factor l_i in h^s: it flips the sign for a wheel whose load is
// positive, where h^v only looks at the distance from the mean.
TEST(LoadDistribution, ExcessVelocityIsSpedUpOnlyBySlipTerm) {
  const MotorVector loads_radps{0.3, -0.2, -0.2, -0.2, -0.2, -0.2, 0.0, 0.0};
  const MotorVector by_variance = variance(loads_radps);
  const MotorVector by_slip = slip(loads_radps);
  EXPECT_NEAR(by_variance[0], -0.3, kTolerance);
  EXPECT_NEAR(by_slip[0], 0.3, kTolerance);
  for (std::size_t i = 1; i < kWheelCount; ++i) {
    EXPECT_NEAR(by_variance[i], 0.06, kTolerance);
    EXPECT_NEAR(by_slip[i], -0.06, kTolerance);
  }
}

// Driving backward mirrors the loads (l → −l) and must mirror the correction: h^v is odd in l
// by itself, h^s through sgn v1.
TEST(LoadDistribution, BackwardMirrorsTheCorrection) {
  const MotorVector forward_loads{0.3, -0.2, -0.1, -0.25, -0.2, 0.05, 0.0, 0.0};
  MotorVector backward_loads{};
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    backward_loads[i] = -forward_loads[i];
  }
  const MotorVector forward_variance = variance(forward_loads);
  const MotorVector backward_variance = variance(backward_loads, -kForwardRadps);
  const MotorVector forward_slip = slip(forward_loads);
  const MotorVector backward_slip = slip(backward_loads, -kForwardRadps);
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    EXPECT_NEAR(backward_variance[i], -forward_variance[i], kTolerance);
    EXPECT_NEAR(backward_slip[i], -forward_slip[i], kTolerance);
  }
}

// Small loads: nothing reaches H, and the result is (6.5), (6.6) exactly as printed.
// l = (−0.1, −0.2, −0.15, −0.2, −0.1, −0.25): l̄ = −0.166667, var = 0.0036667;
// h^v = (−0.020184, 0.010092, −0.005046, 0.010092, −0.020184, 0.025230),
// h^s = (−0.048611, 0.018056, −0.027778, 0.018056, −0.048611, 0.088889).
TEST(LoadDistribution, EqualsThePrintedFormulaWhenNothingIsClipped) {
  const MotorVector loads_radps{-0.1, -0.2, -0.15, -0.2, -0.1, -0.25, 0.0, 0.0};
  const MotorVector expected_variance{-0.020184, 0.010092, -0.005046, 0.010092,
                                      -0.020184, 0.025230, 0.0,       0.0};
  const MotorVector expected_slip{-0.048611, 0.018056, -0.027778, 0.018056,
                                  -0.048611, 0.088889, 0.0,       0.0};
  const MotorVector by_variance = variance(loads_radps);
  const MotorVector by_slip = slip(loads_radps);
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    EXPECT_NEAR(by_variance[i], expected_variance[i], 1e-6);
    EXPECT_NEAR(by_slip[i], expected_slip[i], 1e-6);
  }
}

// The two properties the issue demands, over random loads in [−2, 2] rad/s on both signs of
// v1: Σ h_i = 0 and |h_i| ≤ H; the joints get 0.
TEST(LoadDistribution, SumsToZeroAndStaysWithinHOverRandomLoads) {
  std::mt19937 generator(20080725);
  std::uniform_real_distribution<double> load(-2.0, 2.0);
  const double bound = LoadDistributionParams{}.max_correction_radps;
  for (int trial = 0; trial < 2000; ++trial) {
    MotorVector loads_radps{};
    for (double& value : loads_radps) {
      value = load(generator);
    }
    const double drive_radps = trial % 2 == 0 ? 1.5 : -0.7;
    for (const MotorVector& correction :
         {variance(loads_radps, drive_radps), slip(loads_radps, drive_radps)}) {
      EXPECT_NEAR(wheel_sum(correction), 0.0, kTolerance);
      for (std::size_t i = 0; i < kWheelCount; ++i) {
        EXPECT_LE(std::abs(correction[i]), bound);
      }
      EXPECT_EQ(correction[kFrontJoint], 0.0);
      EXPECT_EQ(correction[kRearJoint], 0.0);
    }
  }
}

TEST(LoadDistribution, NothingWhileNotDriving) {
  const MotorVector loads_radps{-1.0, -0.2, -0.2, -0.2, -0.2, -0.2, 0.5, 0.5};
  EXPECT_EQ(variance(loads_radps, 0.0), MotorVector{});
  EXPECT_EQ(slip(loads_radps, 0.0), MotorVector{});
}

TEST(LoadDistribution, ModeSelectsTheTerm) {
  const MotorVector loads_radps{0.3, -0.2, -0.2, -0.2, -0.2, -0.2, 0.0, 0.0};
  BehaviourSwitches switches;
  switches.load_distribution = LoadDistributionMode::kVariance;
  EXPECT_EQ(load_distribution_radps(loads_radps, 1.0, LoadDistributionParams{}, switches),
            variance(loads_radps));
  switches.load_distribution = LoadDistributionMode::kSlip;
  EXPECT_EQ(load_distribution_radps(loads_radps, 1.0, LoadDistributionParams{}, switches),
            slip(loads_radps));
  switches.load_distribution = LoadDistributionMode::kOff;
  EXPECT_EQ(load_distribution_radps(loads_radps, 1.0, LoadDistributionParams{}, switches),
            MotorVector{});
}

TEST(LoadDistribution, RejectsInvalidInputsByName) {
  MotorVector loads_radps{};
  loads_radps[4] = kNaN;
  EXPECT_THAT(invalid_argument_message([&] { variance(loads_radps); }),
              HasSubstr("variance_load_distribution_radps: loads_radps[4] = nan"));
  EXPECT_THAT(invalid_argument_message([] { slip(MotorVector{}, kNaN); }),
              HasSubstr("slip_load_distribution_radps: drive_speed_radps = nan"));
  LoadDistributionParams params;
  params.max_correction_radps = 0.0;
  EXPECT_THAT(
      invalid_argument_message([&] { slip_load_distribution_radps(MotorVector{}, 1.0, params); }),
      HasSubstr("params.max_correction_radps = 0"));
  BehaviourSwitches off;
  EXPECT_THAT(invalid_argument_message([&] {
                load_distribution_radps(loads_radps, 1.0, LoadDistributionParams{}, off);
              }),
              HasSubstr("load_distribution_radps: loads_radps[4] = nan"));
  const MotorVector huge_radps{1e300, -1e300, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  EXPECT_THAT(invalid_argument_message([&] { slip(huge_radps); }), HasSubstr("overflowed"));
}

}  // namespace
}  // namespace marsokhod::behaviour
