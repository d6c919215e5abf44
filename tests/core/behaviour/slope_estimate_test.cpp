#include "core/behaviour/slope_estimate.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

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
  Vector3 direction = kInitialGravityDirection;
  for (int k = 0; k < cycles; ++k) {
    direction = next_gravity_direction(direction, reading_mps2, kLambda);
  }
  return direction;
}

// On flat ground a = (0, 0, −9.81) and g stays g⁰ = (0, 0, −1): σ = acos(0) − π/2 = 0.
TEST(SlopeEstimate, FlatGroundKeepsTheInitialDirection) {
  const Vector3 direction = settle({0.0, 0.0, -kGravityMps2}, 100);
  EXPECT_NEAR(direction[0], 0.0, kTolerance);
  EXPECT_NEAR(direction[1], 0.0, kTolerance);
  EXPECT_NEAR(direction[2], -1.0, kTolerance);
  EXPECT_NEAR(terrain_slope_rad(direction, 0.3587, 0.3587), 0.0, kTolerance);
}

// λ = 0.5, g⁰, a = (−3, 0, −4) with ‖a‖ = 5: ḡ = 0.5 (0, 0, −1) + 0.5 (−0.6, 0, −0.8)
// = (−0.3, 0, −0.9), ‖ḡ‖ = sqrt(0.9) = 0.948683, g = (−0.316228, 0, −0.948683).
TEST(SlopeEstimate, OneStepByHand) {
  const Vector3 direction =
      next_gravity_direction(kInitialGravityDirection, {-3.0, 0.0, -4.0}, 0.5);
  EXPECT_NEAR(direction[0], -0.3 / std::sqrt(0.9), kTolerance);
  EXPECT_NEAR(direction[1], 0.0, kTolerance);
  EXPECT_NEAR(direction[2], -0.9 / std::sqrt(0.9), kTolerance);
  EXPECT_NEAR(direction[0], -0.316228, 1e-6);
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
  const Vector3 direction =
      next_gravity_direction(kInitialGravityDirection, resting_reading_mps2(pitch_rad), kLambda);
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

// λ = 0: no filtering, g = a/‖a‖. λ = 0.5 against an exactly opposite reading: ḡ = 0, so the
// new reading's direction is taken.
TEST(SlopeEstimate, EdgeCoefficients) {
  const Vector3 unfiltered =
      next_gravity_direction(kInitialGravityDirection, {3.0, 0.0, -4.0}, 0.0);
  EXPECT_NEAR(unfiltered[0], 0.6, kTolerance);
  EXPECT_NEAR(unfiltered[2], -0.8, kTolerance);
  const Vector3 flipped = next_gravity_direction(kInitialGravityDirection, {0.0, 0.0, 9.81}, 0.5);
  EXPECT_EQ(flipped[2], 1.0);
}

TEST(SlopeEstimate, RejectsInvalidInputsByName) {
  EXPECT_THAT(invalid_argument_message([] {
                next_gravity_direction(kInitialGravityDirection, {0.0, kNaN, -9.81}, kLambda);
              }),
              HasSubstr("next_gravity_direction: acceleration_mps2[1] = nan"));
  EXPECT_THAT(invalid_argument_message([] {
                next_gravity_direction(kInitialGravityDirection, {0.0, 0.0, 0.0}, kLambda);
              }),
              HasSubstr("acceleration_mps2 = (0, 0, 0) has no direction"));
  EXPECT_THAT(invalid_argument_message([] {
                next_gravity_direction({0.0, 0.0, 0.0}, {0.0, 0.0, -9.81}, kLambda);
              }),
              HasSubstr("previous_direction = (0, 0, 0)"));
  EXPECT_THAT(invalid_argument_message([] {
                next_gravity_direction(kInitialGravityDirection, {0.0, 0.0, -9.81}, 1.0);
              }),
              HasSubstr("lambda = 1 never learns"));
  EXPECT_THAT(invalid_argument_message([] {
                next_gravity_direction(kInitialGravityDirection, {0.0, 0.0, -9.81}, -0.1);
              }),
              HasSubstr("lambda = -0.1"));
  EXPECT_THAT(
      invalid_argument_message([] { terrain_slope_rad(kInitialGravityDirection, kNaN, 0.0); }),
      HasSubstr("terrain_slope_rad: front_lever_inclination_rad = nan"));
}

}  // namespace
}  // namespace marsokhod::behaviour
