#include "core/mobility/summation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <random>

#include "core/adaptation/motor_curve.hpp"
#include "core/mobility/elementary_motion.hpp"
#include "core/mobility/joint_compensation.hpp"
#include "mobility_test_support.hpp"

namespace marsokhod::mobility {
namespace {

using testing::expect_invalid_argument;
using testing::kInfinity;
using testing::kNaN;

MotorVector filled(double value) {
  MotorVector vector{};
  vector.fill(value);
  return vector;
}

// (5.5)'s bound ζ_i·W(D)·U/Ū with the default W₅₁₁ (W(0.3) = 0.847, Example 4.6), D = 0.3,
// U = 22 V, Ū = 24 V: ζ0 = 0.9896 → 0.9896·0.847·22/24 = 0.768342; ζ3 = 0.941 → 0.730608.
TEST(Summation, BoundsAreScaleTimesCurveTimesVoltageRatio) {
  const Params params;
  const adaptation::MotorCurve curve(params.motor_curves.front());
  const MotorVector bounds = motor_velocity_bounds(params.motors.scale, 0.3, curve, 22.0, 24.0);
  EXPECT_NEAR(bounds[kFrontLeft], 0.768342, 1e-6);
  EXPECT_NEAR(bounds[kCenterRight], 0.730608, 1e-6);
  const MotorVector full = motor_velocity_bounds(params.motors.scale, 1.0, curve, 24.0, 24.0);
  EXPECT_NEAR(full[kRearJoint], 0.9713 * 2.827, 1e-12);
}

// The closed form of chapter 5.4 by hand: |aκ + b| ≤ c.
//   a = 2, b = 1, c = 1.5 (same sign):  κ = (1.5 − 1)/2 = 0.25
//   a = −2, b = 1, c = 1.5 (opposite):  κ = (1.5 + 1)/2 = 1.25
//   a = 3, b = 0, c = 1.5:              κ = 1.5/3 = 0.5
//   a = 0:                               no limit
TEST(Summation, ClosedFormPerMotor) {
  EXPECT_DOUBLE_EQ(driving_scale_limit(2.0, 1.0, 1.5), 0.25);
  EXPECT_DOUBLE_EQ(driving_scale_limit(-2.0, 1.0, 1.5), 1.25);
  EXPECT_DOUBLE_EQ(driving_scale_limit(-2.0, -1.0, 1.5), 0.25);
  EXPECT_DOUBLE_EQ(driving_scale_limit(3.0, 0.0, 1.5), 0.5);
  EXPECT_DOUBLE_EQ(driving_scale_limit(-3.0, 0.0, 1.5), 0.5);
  EXPECT_EQ(driving_scale_limit(0.0, 1.0, 1.5), std::numeric_limits<double>::infinity());
  expect_invalid_argument([] { driving_scale_limit(kNaN, 1.0, 1.5); }, {"driving_radps (a)"});
  expect_invalid_argument([] { driving_scale_limit(1.0, 1.0, kInfinity); }, {"bound_radps (c)"});
}

// Full forward drive 2.5 rad/s on every wheel while the front joint bends (Example 5.4's n6 at
// w6 = 0.5, v6 = 0.5) under bounds of 2.0: the front wheels get −0.563 from walking, the rear
// +0.247, the center +0.298. The tightest motor is BL/BR: κ = (2 − 0.2471)/2.5 = 0.7012 (the
// center's (2 − 0.2980)/2.5 = 0.6808 is tighter still), so κ = 0.6808.
TEST(Summation, DrivingYieldsToWalking) {
  const GeometryParams geometry;  // r = 0.125
  MotorVector walking = front_joint_compensation(-2.1, 0.4, geometry);
  for (double& value : walking) {
    value *= 0.5;
  }
  walking[kFrontJoint] = 0.5;
  MotorVector driving{};
  add_scaled(driving, drive_straight_motion(), 2.5);
  const Summation sum = sum_motions(driving, walking, filled(2.0));
  EXPECT_FALSE(sum.walking_scaled);
  EXPECT_EQ(sum.walking_scale, 1.0);
  EXPECT_NEAR(sum.driving_scale, (2.0 - 0.5 * 0.595902) / 2.5, 1e-6);
  EXPECT_NEAR(sum.velocities_radps[kCenterLeft], 2.0, 1e-12);
  EXPECT_NEAR(sum.velocities_radps[kFrontJoint], 0.5, 1e-15);
}

// A feasible sum passes unchanged: κ = 1, ŵ = driving + walking.
TEST(Summation, FeasibleSumIsUnchanged) {
  const MotorVector driving{1.0, -1.0, 0.5, 0.5, 1.0, -1.0, 0.0, 0.0};
  const MotorVector walking{0.5, 0.5, 0.2, 0.2, -0.1, -0.1, 0.3, -0.3};
  const Summation sum = sum_motions(driving, walking, filled(1.5));
  EXPECT_EQ(sum.driving_scale, 1.0);
  EXPECT_FALSE(sum.walking_scaled);
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    EXPECT_EQ(sum.velocities_radps[i], driving[i] + walking[i]);
  }
}

// (5.6) violated: walking 3.0 on FL against a bound of 1.5 → λ = 0.5, reported; the driving part
// then fits into what is left (FL: walking 1.5 = bound, driving 1 same sign → κ = 0).
TEST(Summation, WalkingAloneTooFastIsScaledAndReported) {
  MotorVector walking{};
  walking[kFrontLeft] = 3.0;
  walking[kFrontJoint] = 1.0;
  MotorVector driving{};
  add_scaled(driving, drive_straight_motion(), 1.0);
  const Summation sum = sum_motions(driving, walking, filled(1.5));
  EXPECT_TRUE(sum.walking_scaled);
  EXPECT_DOUBLE_EQ(sum.walking_scale, 0.5);
  EXPECT_EQ(sum.driving_scale, 0.0);
  EXPECT_DOUBLE_EQ(sum.velocities_radps[kFrontLeft], 1.5);
  EXPECT_DOUBLE_EQ(sum.velocities_radps[kFrontJoint], 0.5);
}

// Properties over random inputs (fixed seed): every |ŵ_i| ≤ bound_i; κ = 1 (and λ = 1) whenever
// the unscaled sum is feasible; κ is the largest: κ + 1e-9 violates some bound unless κ = 1.
TEST(Summation, PropertiesOverRandomInputs) {
  std::mt19937 random(54);
  std::uniform_real_distribution<double> velocity(-4.0, 4.0);
  std::uniform_real_distribution<double> walking_velocity(-1.5, 1.5);
  std::uniform_real_distribution<double> bound(0.0, 2.8);
  std::uniform_int_distribution<int> zero(0, 9);
  for (int n = 0; n < 5000; ++n) {
    MotorVector driving{};
    MotorVector walking{};
    MotorVector bounds{};
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      driving[i] = zero(random) == 0 ? 0.0 : velocity(random);
      walking[i] = zero(random) == 0 ? 0.0 : walking_velocity(random);
      bounds[i] = bound(random);
    }
    const Summation sum = sum_motions(driving, walking, bounds);
    bool feasible = true;
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      ASSERT_LE(std::abs(sum.velocities_radps[i]), bounds[i] + 1e-12) << n << " motor " << i;
      feasible = feasible && std::abs(driving[i] + walking[i]) <= bounds[i];
    }
    ASSERT_GE(sum.driving_scale, 0.0);
    ASSERT_LE(sum.driving_scale, 1.0);
    if (feasible) {
      ASSERT_EQ(sum.driving_scale, 1.0) << n;
      ASSERT_FALSE(sum.walking_scaled) << n;
    }
    if (sum.driving_scale < 1.0) {
      bool violated = false;
      for (std::size_t i = 0; i < kMotorCount; ++i) {
        const double larger =
            (sum.driving_scale + 1e-9) * driving[i] + sum.walking_scale * walking[i];
        violated = violated || std::abs(larger) > bounds[i];
      }
      ASSERT_TRUE(violated) << n << ": κ = " << sum.driving_scale << " is not the largest";
    }
  }
}

TEST(Summation, RejectsInvalidInputsNamingThem) {
  MotorVector bad{};
  bad[3] = kNaN;
  expect_invalid_argument([&] { sum_motions(bad, MotorVector{}, filled(1.0)); },
                          {"driving_radps[3] (CR)"});
  expect_invalid_argument([&] { sum_motions(MotorVector{}, bad, filled(1.0)); },
                          {"walking_radps[3] (CR)"});
  MotorVector negative = filled(1.0);
  negative[7] = -0.1;
  expect_invalid_argument([&] { sum_motions(MotorVector{}, MotorVector{}, negative); },
                          {"bounds_radps[7] (AR)", "≥ 0"});
  const Params params;
  const adaptation::MotorCurve curve(params.motor_curves.front());
  expect_invalid_argument(
      [&] { motor_velocity_bounds(params.motors.scale, 0.0, curve, 24.0, 24.0); }, {"max_duty"});
  expect_invalid_argument(
      [&] { motor_velocity_bounds(params.motors.scale, 0.5, curve, kInfinity, 24.0); },
      {"supply_v (U)"});
  expect_invalid_argument(
      [&] { motor_velocity_bounds(params.motors.scale, 0.5, curve, 24.0, 0.0); },
      {"nominal_supply_v"});
}

}  // namespace
}  // namespace marsokhod::mobility
