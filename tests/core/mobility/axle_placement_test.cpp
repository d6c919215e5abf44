#include "core/mobility/axle_placement.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>

#include "core/mobility/joint_compensation.hpp"
#include "core/mobility/lever_geometry.hpp"
#include "mobility_test_support.hpp"

namespace marsokhod::mobility {
namespace {

using testing::expect_invalid_argument;
using testing::kInfinity;
using testing::kNaN;

double objective(const AxleDistanceRates& rates, const AxleFactors& factors) {
  const ExteriorAxleVelocities axles = exterior_axle_velocities(rates, factors);
  return axles.front_mps * axles.front_mps + axles.rear_mps * axles.rear_mps;
}

// Remark 5.5: ϱ⁰ = 0; v1ᵈ > 0 → 0, v1ᵈ < 0 → 1, v1ᵈ = 0 keeps the last intention.
TEST(AxlePlacement, DrivingIntentRemembersTheLastDirection) {
  DrivingIntent intent = DrivingIntent::kForward;
  const double targets[] = {0.0, -0.3, 0.0, 0.0, 2.0, 0.0, -1e-9};
  const double expected[] = {0, 1, 1, 1, 0, 0, 1};
  for (std::size_t k = 0; k < 7; ++k) {
    intent = driving_intent(intent, targets[k]);
    EXPECT_EQ(intent_value(intent), expected[k]) << k;
  }
}

// Remark 5.5's table: increase → (1 − ϱ, ϱ), decrease → (ϱ, 1 − ϱ); and its example: increasing
// cr after backing up (ϱ = 1) gives ρr = 1.
TEST(AxlePlacement, RhoTableOfRemark55) {
  using enum ClearanceIntent;
  EXPECT_EQ(front_axle_factor(DrivingIntent::kForward, kIncrease), 1.0);
  EXPECT_EQ(rear_axle_factor(DrivingIntent::kForward, kIncrease), 0.0);
  EXPECT_EQ(front_axle_factor(DrivingIntent::kForward, kDecrease), 0.0);
  EXPECT_EQ(rear_axle_factor(DrivingIntent::kForward, kDecrease), 1.0);
  EXPECT_EQ(front_axle_factor(DrivingIntent::kBackward, kIncrease), 0.0);
  EXPECT_EQ(rear_axle_factor(DrivingIntent::kBackward, kIncrease), 1.0);
  EXPECT_EQ(front_axle_factor(DrivingIntent::kBackward, kDecrease), 1.0);
  EXPECT_EQ(rear_axle_factor(DrivingIntent::kBackward, kDecrease), 0.0);
}

// p6 = −γf and p7 = +γr: the front extends for w6 < 0, the rear for w7 > 0.
TEST(AxlePlacement, ClearanceIntentFromTheJointVelocity) {
  EXPECT_EQ(front_clearance_intent(-0.2), ClearanceIntent::kIncrease);
  EXPECT_EQ(front_clearance_intent(0.2), ClearanceIntent::kDecrease);
  EXPECT_EQ(rear_clearance_intent(0.2), ClearanceIntent::kIncrease);
  EXPECT_EQ(rear_clearance_intent(-0.2), ClearanceIntent::kDecrease);
}

// yf = (ab·sin γf/cf)·w6 at p6 = −2.1, w6 = 1: 0.059885·0.863209/0.502055 = 0.102963 m/s, and
// it is −∂t cf (finite difference of cf along p6). yr = +∂t cr.
TEST(AxlePlacement, AxleDistanceRatesInTheMotorSign) {
  const GeometryParams geometry;
  const AxleDistanceRates rates = axle_distance_rates(-2.1, 1.85, 1.0, 1.0, geometry);
  EXPECT_NEAR(rates.front_mps, 0.102963, 1e-6);
  const double step = 1e-6;
  const double front_clearance_rate = (front_lever(-2.1 + step, geometry).clearance_m -
                                       front_lever(-2.1 - step, geometry).clearance_m) /
                                      (2 * step);
  const double rear_clearance_rate = (rear_lever(1.85 + step, geometry).clearance_m -
                                      rear_lever(1.85 - step, geometry).clearance_m) /
                                     (2 * step);
  EXPECT_NEAR(rates.front_mps, -front_clearance_rate, 1e-8);
  EXPECT_NEAR(rates.rear_mps, rear_clearance_rate, 1e-8);
}

// docs/design.md: af = yr − q and ar = yf − q are what the rows of n6·w6 + n7·w7 roll the exterior
// axles at: r·(wheel rate minus the wheel's own angle term). Random states and factors.
TEST(AxlePlacement, ExteriorAxleVelocitiesAreWhatTheCompensationRolls) {
  const GeometryParams geometry;
  std::mt19937 random(51);
  std::uniform_real_distribution<double> gamma(1.22, 2.55);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    const double p6 = -gamma(random);
    const double p7 = gamma(random);
    const double w6 = unit(random);
    const double w7 = unit(random);
    const AxleFactors factors{unit(random), unit(random)};
    const MotorVector w =
        walking_motion({p6, p7, 0.0, 0.0, w6, w7, factors.front, factors.rear}, geometry);
    const double front_turn = lever_rates(-p6, geometry).exterior_angle_rate;
    const double rear_turn = lever_rates(p7, geometry).exterior_angle_rate;
    const ExteriorAxleVelocities axles =
        exterior_axle_velocities(axle_distance_rates(p6, p7, w6, w7, geometry), factors);
    const double r = geometry.wheel_radius_m;
    ASSERT_NEAR(r * (w[kFrontLeft] + front_turn * w6), axles.front_mps, 1e-12);
    ASSERT_NEAR(r * (w[kBackRight] + rear_turn * w7), axles.rear_mps, 1e-12);
  }
}

// No joint moving: (ε, 1 − ε). Equal rates: (ε, 1 − ε) is already on the minimiser line
// ρf + ρr = 1 (e.g. yf = yr = 1, ε = 0.3: ρf = (1 − 0.4 + 0.6)/4 = 0.3, ρr = (1.4 + 0.4 + 1)/4 =
// 0.7).
TEST(AxlePlacement, DegenerateRatesGiveEpsilon) {
  const AxleFactors still = two_joint_axle_factors({0.0, 0.0}, 0.3);
  EXPECT_EQ(still.front, 0.3);
  EXPECT_EQ(still.rear, 0.7);
  const AxleFactors equal = two_joint_axle_factors({1.0, 1.0}, 0.3);
  EXPECT_NEAR(equal.front, 0.3, 1e-15);
  EXPECT_NEAR(equal.rear, 0.7, 1e-15);
  const AxleFactors tiny = two_joint_axle_factors({1e-200, 1e-200}, 0.3);
  EXPECT_NEAR(tiny.front, 0.3, 1e-15);
  const AxleFactors one = two_joint_axle_factors({1.0, 0.0}, 0.0);  // ρf = ½, ρr = 1 − ε
  EXPECT_NEAR(one.front, 0.5, 1e-15);
  EXPECT_NEAR(one.rear, 1.0, 1e-15);
}

// The printed formula minimises af² + ar² (its value (yf − yr)²/2 is below every point of a
// 201 × 201 grid over [−2, 3]²) and is the point of the minimiser line q = (yf + yr)/2 nearest to
// (ε, 1 − ε) (a brute-force scan along the line). Random rates and ε, fixed seed.
TEST(AxlePlacement, EpsilonFormulaIsTheNearestMinimiser) {
  std::mt19937 random(53);
  std::uniform_real_distribution<double> rate(-1.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 300; ++i) {
    const AxleDistanceRates rates{rate(random), rate(random)};
    const double epsilon = unit(random);
    const AxleFactors best = two_joint_axle_factors(rates, epsilon);
    const double least = objective(rates, best);
    const double difference = rates.front_mps - rates.rear_mps;
    ASSERT_NEAR(least, 0.5 * difference * difference, 1e-12);
    for (int x = 0; x <= 200; ++x) {
      for (int y = 0; y <= 200; ++y) {
        const AxleFactors grid{-2.0 + 0.025 * x, -2.0 + 0.025 * y};
        ASSERT_GE(objective(rates, grid), least - 1e-12);
      }
    }
    // Along the line: best + t·(yr, −yf)/|y| keeps q; scan t ∈ [−3, 3].
    const double norm = std::hypot(rates.front_mps, rates.rear_mps);
    const double along_front = rates.rear_mps / norm;
    const double along_rear = -rates.front_mps / norm;
    double nearest_t = std::numeric_limits<double>::infinity();
    double nearest_distance = std::numeric_limits<double>::infinity();
    for (int k = -3000; k <= 3000; ++k) {
      const double t = 0.001 * k;
      const AxleFactors point{best.front + t * along_front, best.rear + t * along_rear};
      ASSERT_NEAR(objective(rates, point), least, 1e-9);
      const double distance = std::hypot(point.front - epsilon, point.rear - (1.0 - epsilon));
      if (distance < nearest_distance) {
        nearest_distance = distance;
        nearest_t = t;
      }
    }
    ASSERT_LE(std::abs(nearest_t), 0.0005) << i;
  }
}

// The wheels see ρ only through q, so ε does not change the motion (only the representative).
TEST(AxlePlacement, EpsilonDoesNotChangeTheWheelVelocities) {
  const GeometryParams geometry;
  const AxleDistanceRates rates = axle_distance_rates(-1.7, 2.2, 0.4, 0.9, geometry);
  const AxleFactors zero = two_joint_axle_factors(rates, 0.0);
  const MotorVector reference =
      walking_motion({-1.7, 2.2, 0.0, 0.0, 0.4, 0.9, zero.front, zero.rear}, geometry);
  for (const double epsilon : {0.25, 0.5, 1.0}) {
    const AxleFactors factors = two_joint_axle_factors(rates, epsilon);
    const MotorVector w =
        walking_motion({-1.7, 2.2, 0.0, 0.0, 0.4, 0.9, factors.front, factors.rear}, geometry);
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      ASSERT_NEAR(w[i], reference[i], 1e-12) << epsilon << " " << kMotorNames[i];
    }
  }
}

// yf = 1, yr = 3, ε = 0: ρf = (1 − 3 + 0)/20 = −0.1 — outside [0, 1], as documented.
TEST(AxlePlacement, EpsilonFormulaMayLeaveTheUnitInterval) {
  EXPECT_NEAR(two_joint_axle_factors({1.0, 3.0}, 0.0).front, -0.1, 1e-15);
}

// On a slope the mismatch goes uphill: yf = 0.02, yr = 0.01 m/s (the front joint contracting
// faster), forward uphill. q = min = 0.01: the front anchor stands (af = yr − q = 0), the rear is
// asked uphill by the difference (ar = yf − q = 0.01), the centre advances at the faster joint's
// 0.02. ρ: the line ρf + ρr/2 = 1/2 (rates over the larger) nearest to (½, ½) is
// (½, ½) − 0.2·(1, ½) = (0.3, 0.4). Backward uphill, q = max = 0.02: the front anchor goes back
// (uphill) by 0.01, the rear stands, (½, ½) + 0.2·(1, ½) = (0.7, 0.6). The printed formula
// instead asks one anchor downhill: af = −0.005.
TEST(AxlePlacement, OnASlopeTheJointsMismatchGoesUphill) {
  const AxleDistanceRates rates{0.02, 0.01};
  const AxleFactors up = uphill_axle_factors(rates, 0.5, 1.0);
  EXPECT_NEAR(up.front, 0.3, 1e-15);
  EXPECT_NEAR(up.rear, 0.4, 1e-15);
  const ExteriorAxleVelocities up_axles = exterior_axle_velocities(rates, up);
  EXPECT_NEAR(up_axles.front_mps, 0.0, 1e-17);
  EXPECT_NEAR(up_axles.rear_mps, 0.01, 1e-17);
  const AxleFactors down = uphill_axle_factors(rates, 0.5, -1.0);
  EXPECT_NEAR(down.front, 0.7, 1e-15);
  EXPECT_NEAR(down.rear, 0.6, 1e-15);
  const ExteriorAxleVelocities down_axles = exterior_axle_velocities(rates, down);
  EXPECT_NEAR(down_axles.front_mps, -0.01, 1e-17);
  EXPECT_NEAR(down_axles.rear_mps, 0.0, 1e-17);
  EXPECT_NEAR(exterior_axle_velocities(rates, two_joint_axle_factors(rates, 0.5)).front_mps,
              -0.005, 1e-17);
  // Equal rates: the printed formula's motion (q is the mean either way).
  const AxleFactors equal = uphill_axle_factors({0.013, 0.013}, 0.5, 1.0);
  EXPECT_NEAR(equal.front, 0.5, 1e-15);
  EXPECT_NEAR(equal.rear, 0.5, 1e-15);
  // Still joints: (ε, 1 − ε).
  const AxleFactors still = uphill_axle_factors({0.0, 0.0}, 0.25, -1.0);
  EXPECT_EQ(still.front, 0.25);
  EXPECT_EQ(still.rear, 0.75);
}

// Every pair of rates, ε and side: ρ in [0, 1]², no anchor asked downhill, q at the uphill end
// (the centre at the faster joint's rate forward-uphill, the slower's backward-uphill), and ρ the
// point of that line inside the square nearest to (ε, 1 − ε) (a scan along the line).
TEST(AxlePlacement, UphillFactorsAskNoAnchorDownhillAndStayNearEpsilon) {
  std::mt19937 random(71);
  std::uniform_real_distribution<double> rate(-1.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    AxleDistanceRates rates{rate(random), rate(random)};
    if (i % 10 == 0) rates.rear_mps = 0.0;  // one joint still
    if (i % 10 == 1) rates.rear_mps = rates.front_mps;
    const double epsilon = i % 10 == 2 ? 1.0 : unit(random);
    const double uphill = i % 2 == 0 ? 1.0 : -1.0;
    SCOPED_TRACE(i);
    const AxleFactors rho = uphill_axle_factors(rates, epsilon, uphill);
    ASSERT_GE(rho.front, 0.0);
    ASSERT_LE(rho.front, 1.0);
    ASSERT_GE(rho.rear, 0.0);
    ASSERT_LE(rho.rear, 1.0);
    const ExteriorAxleVelocities axles = exterior_axle_velocities(rates, rho);
    ASSERT_GE(uphill * axles.front_mps, -1e-15);
    ASSERT_GE(uphill * axles.rear_mps, -1e-15);
    const double q = rho.front * rates.front_mps + rho.rear * rates.rear_mps;
    const double wanted = uphill > 0.0 ? std::min(rates.front_mps, rates.rear_mps)
                                       : std::max(rates.front_mps, rates.rear_mps);
    ASSERT_NEAR(q, wanted, 1e-14);
    // Along the line through ρ (direction (yr, −yf)/|y|), inside the square, no point is nearer.
    const double norm = std::hypot(rates.front_mps, rates.rear_mps);
    const double distance = std::hypot(rho.front - epsilon, rho.rear - (1.0 - epsilon));
    for (int k = -2000; k <= 2000; ++k) {
      const double t = 0.001 * k;
      const AxleFactors point{rho.front + t * rates.rear_mps / norm,
                              rho.rear - t * rates.front_mps / norm};
      if (point.front < 0.0 || point.front > 1.0 || point.rear < 0.0 || point.rear > 1.0) continue;
      ASSERT_GE(std::hypot(point.front - epsilon, point.rear - (1.0 - epsilon)), distance - 1e-12)
          << t;
    }
  }
}

TEST(AxlePlacement, RejectsInvalidInputsNamingThem) {
  expect_invalid_argument([] { driving_intent(DrivingIntent::kForward, kNaN); }, {"v1ᵈ"});
  expect_invalid_argument([] { two_joint_axle_factors({kNaN, 0.0}, 0.5); }, {"yf"});
  expect_invalid_argument([] { two_joint_axle_factors({0.0, kInfinity}, 0.5); }, {"yr"});
  expect_invalid_argument([] { two_joint_axle_factors({0.0, 0.0}, 1.5); }, {"epsilon", "[0, 1]"});
  expect_invalid_argument([] { exterior_axle_velocities({0.0, 0.0}, {kNaN, 0.0}); }, {"ρf"});
  expect_invalid_argument([] { uphill_axle_factors({0.1, 0.2}, 0.5, 0.0); }, {"uphill", "+1 or -1"});
  expect_invalid_argument([] { uphill_axle_factors({kNaN, 0.2}, 0.5, 1.0); }, {"yf"});
  expect_invalid_argument([] { uphill_axle_factors({0.1, 0.2}, -0.5, 1.0); }, {"epsilon"});
  expect_invalid_argument([] { axle_distance_rates(-2.0, 2.0, 0.0, kNaN, GeometryParams{}); },
                          {"w7"});
  expect_invalid_argument([] { front_clearance_intent(kNaN); }, {"w6"});
}

}  // namespace
}  // namespace marsokhod::mobility
