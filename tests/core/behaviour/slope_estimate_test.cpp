#include "core/behaviour/slope_estimate.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "behaviour_test_support.hpp"

namespace marsokhod::behaviour {
namespace {

using test::invalid_argument_message;
using test::kNaN;
using ::testing::HasSubstr;

constexpr double kTolerance = 1e-12;
constexpr double kGravityMps2 = 9.81;
constexpr double kLambda = 0.95;  // FilterParams::gravity_lambda

// The accelerometer at rest, pitched by θ (nose up for θ > 0): gravity seen in the sensor
// frame, x1 forward, x3 up.
Vector3 resting_reading_mps2(double pitch_rad) {
  return {-kGravityMps2 * std::sin(pitch_rad), 0.0, -kGravityMps2 * std::cos(pitch_rad)};
}

Vector3 settle(const Vector3& reading_mps2, int cycles) {
  GravityEstimate estimate(kGravityMps2);
  for (int k = 0; k < cycles; ++k) {
    estimate.update(reading_mps2, kLambda);
  }
  return estimate.direction();
}

// One update from ā⁰ = (0, 0, −9.81).
Vector3 one_step(const Vector3& reading_mps2, double lambda) {
  GravityEstimate estimate(kGravityMps2);
  estimate.update(reading_mps2, lambda);
  return estimate.direction();
}

// On flat ground a = (0, 0, −9.81) and g stays g⁰ = (0, 0, −1): σ = acos(0) − π/2 = 0.
// 6.2.1's dead band (0.05 rad, ≈ 3°): within it σ counts as flat; from its edge on σ is taken as it
// is, and its sign says which way is uphill.
TEST(SlopeEstimate, WithinTheDeadBandASlopeCountsAsFlat) {
  const BehaviourParams params;
  ASSERT_EQ(params.slant_deadband_rad, 0.05);
  for (const double sigma : {0.0, 0.0499, -0.0499}) {
    EXPECT_EQ(slope_beyond_dead_band(sigma, params), 0.0) << sigma;
    EXPECT_EQ(uphill_side(sigma, params), 0.0) << sigma;
  }
  for (const double sigma : {0.05, 0.35, -0.05, -0.35}) {
    EXPECT_EQ(slope_beyond_dead_band(sigma, params), sigma) << sigma;
    EXPECT_EQ(uphill_side(sigma, params), sigma > 0.0 ? 1.0 : -1.0) << sigma;
  }
}

TEST(SlopeEstimate, FlatGroundKeepsTheInitialDirection) {
  const Vector3 direction = settle({0.0, 0.0, -kGravityMps2}, 100);
  EXPECT_NEAR(direction[0], 0.0, kTolerance);
  EXPECT_NEAR(direction[1], 0.0, kTolerance);
  EXPECT_NEAR(direction[2], -1.0, kTolerance);
  EXPECT_NEAR(terrain_slope_rad(direction, 0.3587, 0.3587), 0.0, kTolerance);
}

// λ = 0.5, ā⁰ = (0, 0, −9.81), a = (−3, 0, −4): ā = 0.5 (0, 0, −9.81) + 0.5 (−3, 0, −4)
// = (−1.5, 0, −6.905), ‖ā‖ = 7.066046, g = (−0.212283, 0, −0.977208).
TEST(SlopeEstimate, OneStepByHand) {
  GravityEstimate estimate(kGravityMps2);
  estimate.update({-3.0, 0.0, -4.0}, 0.5);
  EXPECT_NEAR(estimate.mean_acceleration_mps2()[0], -1.5, kTolerance);
  EXPECT_NEAR(estimate.mean_acceleration_mps2()[2], -6.905, kTolerance);
  const Vector3 direction = estimate.direction();
  const double length = std::hypot(1.5, 6.905);
  EXPECT_NEAR(direction[0], -1.5 / length, kTolerance);
  EXPECT_NEAR(direction[1], 0.0, kTolerance);
  EXPECT_NEAR(direction[2], -6.905 / length, kTolerance);
  EXPECT_NEAR(direction[0], -0.212283, 1e-6);
}

// Bumps do not tilt the estimate: on a 20° pitch the reading's vertical component varies by
// ±3 m/s² (loose sand), half the cycles each way. The mean of the readings is gravity, so σ
// settles at 20°; the thesis' mean of the readings' directions, by hand: the two readings
// point 28.35° and 15.36° off the vertical, their unit vectors average to 21.86°.
TEST(SlopeEstimate, VerticalBumpsDoNotBiasTheSlope) {
  const double pitch_rad = 20.0 * std::numbers::pi / 180.0;
  const Vector3 rest = resting_reading_mps2(pitch_rad);
  const Vector3 up{rest[0], 0.0, rest[2] + 3.0};
  const Vector3 down{rest[0], 0.0, rest[2] - 3.0};
  GravityEstimate estimate(kGravityMps2);
  Vector3 thesis_mean{};
  for (int k = 0; k < 4000; ++k) {
    // λ = 0.99 as configured: ā forgets the start (0.99^4000 ≈ 3e-18) and keeps half a bump.
    const Vector3& reading = k % 2 == 0 ? up : down;
    estimate.update(reading, 0.99);
    const double length = std::hypot(reading[0], reading[1], reading[2]);
    for (std::size_t i = 0; i < 3; ++i) thesis_mean[i] += reading[i] / length / 4000.0;
  }
  // ā still carries the alternation, ±(1 − λ)/(1 + λ)·3 = ±0.0151 m/s² along x3, which tilts
  // it by 0.0151·sin 20°/9.81 = 0.00053 rad (0.03°) either way: within 0.001 rad of 20°.
  EXPECT_NEAR(terrain_slope_rad(estimate.direction(), 0.0, 0.0), pitch_rad, 1e-3);
  const double thesis_length = std::hypot(thesis_mean[0], thesis_mean[2]);
  const double thesis_rad = terrain_slope_rad(
      {thesis_mean[0] / thesis_length, 0.0, thesis_mean[2] / thesis_length}, 0.0, 0.0);
  EXPECT_NEAR(thesis_rad * 180.0 / std::numbers::pi, 21.86, 0.01);
}

// The estimate is a unit vector and converges to the reading's direction: the angle to it
// shrinks about by λ per cycle, 0.95^700 ≈ 2.5e-16.
TEST(SlopeEstimate, ConvergesToAConstantReading) {
  const double pitch_rad = 15.0 * std::numbers::pi / 180.0;
  const Vector3 direction = settle(resting_reading_mps2(pitch_rad), 700);
  EXPECT_NEAR(std::hypot(direction[0], direction[1], direction[2]), 1.0, kTolerance);
  EXPECT_NEAR(direction[0], -std::sin(pitch_rad), kTolerance);
  EXPECT_NEAR(direction[2], -std::cos(pitch_rad), kTolerance);
}

// The filter smooths: after one cycle on a 15° reading the estimate has moved, but by far
// less than 15°.
TEST(SlopeEstimate, OneCycleMovesOnlyAFraction) {
  const double pitch_rad = 15.0 * std::numbers::pi / 180.0;
  const Vector3 direction = one_step(resting_reading_mps2(pitch_rad), kLambda);
  const double slope_rad = terrain_slope_rad(direction, 0.0, 0.0);
  EXPECT_GT(slope_rad, 0.0);
  EXPECT_LT(slope_rad, 0.1 * pitch_rad);
}

// Sign convention: nose up by θ reads a1 = −9.81 sin θ < 0, g1 = −sin θ, acos(g1) = π/2 + θ,
// so σ = θ > 0 (uphill); nose down reads a1 > 0 and gives σ = −θ.
TEST(SlopeEstimate, NoseUpIsAPositiveSlope) {
  const double pitch_rad = 15.0 * std::numbers::pi / 180.0;
  const Vector3 nose_up = settle(resting_reading_mps2(pitch_rad), 700);
  EXPECT_LT(resting_reading_mps2(pitch_rad)[0], 0.0);
  EXPECT_NEAR(terrain_slope_rad(nose_up, 0.3587, 0.3587), pitch_rad, 1e-9);
  const Vector3 nose_down = settle(resting_reading_mps2(-pitch_rad), 700);
  EXPECT_NEAR(terrain_slope_rad(nose_down, 0.3587, 0.3587), -pitch_rad, 1e-9);
}

// g = g⁰, αf = 0.3, αr = 0.5: σ = π/2 − π/2 + (0.5 − 0.3)/2 = 0.1.
TEST(SlopeEstimate, LeverInclinationsCorrectTheSlope) {
  EXPECT_NEAR(terrain_slope_rad(kInitialGravityDirection, 0.3, 0.5), 0.1, kTolerance);
  EXPECT_NEAR(terrain_slope_rad(kInitialGravityDirection, 0.5, 0.3), -0.1, kTolerance);
}

// g1 a rounding beyond −1 is clamped: acos(−1) − π/2 = π/2.
TEST(SlopeEstimate, ClampsTheForwardComponent) {
  EXPECT_NEAR(terrain_slope_rad({-1.0 - 1e-15, 0.0, 0.0}, 0.0, 0.0), std::numbers::pi / 2.0,
              kTolerance);
}

// λ = 0: no filtering, g = a/‖a‖. λ = 0.5 against an exactly opposite reading: ā = 0, so the
// reading is taken.
TEST(SlopeEstimate, EdgeCoefficients) {
  const Vector3 unfiltered = one_step({3.0, 0.0, -4.0}, 0.0);
  EXPECT_NEAR(unfiltered[0], 0.6, kTolerance);
  EXPECT_NEAR(unfiltered[2], -0.8, kTolerance);
  const Vector3 flipped = one_step({0.0, 0.0, 9.81}, 0.5);
  EXPECT_EQ(flipped[2], 1.0);
}

// Flat ground, a joint bending: the levers' half difference ramps from 0 to 0.10 rad over 3 s at
// 64 Hz and the centre unit pitches against it, −(αr − αf)/2, as front-wheel walking pitches it
// in the simulator. Filtered alike, pitch and correction cancel: |σ| stays under 1e-3 rad (the
// residue: the filter averages vectors, not angles). With the correction unfiltered, as the
// thesis adds it, σ reads the filter's lag behind a ramp of m per cycle, e_k = λm(1 − λ^k)/(1 − λ):
// 0.044 rad after the 192 cycles, near the slant dead band (0.05 rad); joints that bend faster
// pass it.
TEST(SlopeEstimate, ALeverBendingOnFlatGroundIsNotASlope) {
  constexpr double kDriverLambda = 0.99;  // the configuration's, 1.6 s at 64 Hz
  SlopeEstimate estimate(kGravityMps2);
  GravityEstimate gravity_only(kGravityMps2);
  double worst = 0.0, worst_unfiltered = 0.0;
  constexpr int kRampCycles = 64 * 3;
  for (int k = 0; k < 64 * 15; ++k) {
    const double half_difference = 0.10 * std::min(1.0, static_cast<double>(k) / kRampCycles);
    const double front = 0.3587 - half_difference, rear = 0.3587 + half_difference;
    const Vector3 reading = resting_reading_mps2(-half_difference);
    estimate.update(reading, front, rear, kDriverLambda);
    gravity_only.update(reading, kDriverLambda);
    worst = std::max(worst, std::abs(estimate.slope_rad()));
    const double unfiltered = terrain_slope_rad(gravity_only.direction(), front, rear);
    worst_unfiltered = std::max(worst_unfiltered, std::abs(unfiltered));
  }
  EXPECT_LT(worst, 1e-3);
  const double m = 0.10 / kRampCycles;
  const double lag = kDriverLambda * m * (1.0 - std::pow(kDriverLambda, kRampCycles)) /
                     (1.0 - kDriverLambda);
  EXPECT_NEAR(worst_unfiltered, lag, 1e-3);
  // The correction has settled on the levers' half difference, and σ on flat ground.
  EXPECT_NEAR(estimate.lever_correction_rad(), 0.10, 1e-4);
  EXPECT_NEAR(estimate.slope_rad(), 0.0, 1e-4);
}

// On a slope θ, the levers still, σ converges to θ as the gravity filter does; by hand after one
// step from flat: c¹ = (1 − λ)(αr − αf)/2.
TEST(SlopeEstimate, TheFilteredCorrectionConvergesToTheSlope) {
  SlopeEstimate estimate(kGravityMps2);
  estimate.update(resting_reading_mps2(0.0), 0.3, 0.5, kLambda);
  EXPECT_NEAR(estimate.lever_correction_rad(), (1.0 - kLambda) * 0.1, kTolerance);
  const double pitch_rad = 0.2;  // the centre unit's, the levers adding 0.1
  for (int k = 0; k < 700; ++k) estimate.update(resting_reading_mps2(pitch_rad), 0.3, 0.5, kLambda);
  EXPECT_NEAR(estimate.slope_rad(), pitch_rad + 0.1, 1e-9);
}

TEST(SlopeEstimate, RejectsInvalidInputsByName) {
  GravityEstimate estimate(kGravityMps2);
  EXPECT_THAT(invalid_argument_message([&] { estimate.update({0.0, kNaN, -9.81}, kLambda); }),
              HasSubstr("GravityEstimate::update: acceleration_mps2[1] = nan"));
  EXPECT_THAT(invalid_argument_message([&] { estimate.update({0.0, 0.0, 0.0}, kLambda); }),
              HasSubstr("acceleration_mps2 = (0, 0, 0) has no direction"));
  EXPECT_THAT(invalid_argument_message([] { GravityEstimate bad(0.0); }),
              HasSubstr("gravity_mps2"));
  EXPECT_THAT(invalid_argument_message([&] { estimate.update({0.0, 0.0, -9.81}, 1.0); }),
              HasSubstr("lambda = 1 never learns"));
  EXPECT_THAT(invalid_argument_message([&] { estimate.update({0.0, 0.0, -9.81}, -0.1); }),
              HasSubstr("lambda = -0.1"));
  // Refused readings leave the estimate where it was: still flat.
  EXPECT_EQ(estimate.direction(), kInitialGravityDirection);
  EXPECT_THAT(
      invalid_argument_message([] { terrain_slope_rad(kInitialGravityDirection, kNaN, 0.0); }),
      HasSubstr("terrain_slope_rad: front_lever_inclination_rad = nan"));
  // The slope estimate refuses a bad inclination or reading whole: neither filter moves.
  SlopeEstimate slope(kGravityMps2);
  EXPECT_THAT(invalid_argument_message(
                  [&] { slope.update(resting_reading_mps2(0.1), 0.3, kNaN, kLambda); }),
              HasSubstr("SlopeEstimate::update: rear_lever_inclination_rad = nan"));
  EXPECT_THAT(invalid_argument_message([&] { slope.update({0.0, 0.0, 0.0}, 0.3, 0.5, kLambda); }),
              HasSubstr("has no direction"));
  EXPECT_EQ(slope.lever_correction_rad(), 0.0);
  EXPECT_EQ(slope.gravity().direction(), kInitialGravityDirection);
}

}  // namespace
}  // namespace marsokhod::behaviour
