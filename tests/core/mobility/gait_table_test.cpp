#include "core/mobility/gait_table.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <stdexcept>

#include "core/mobility/lever_geometry.hpp"
#include "mobility_test_support.hpp"

namespace marsokhod::mobility {
namespace {

using testing::expect_invalid_argument;
using testing::kNaN;
using enum JointStroke;

constexpr std::array<Gait, 5> kGaits{Gait::kRolking, Gait::kFrontWheelWalking,
                                     Gait::kRearWheelWalking, Gait::kWormLike,
                                     Gait::kRolkingExtendedBase};

void expect_state(const GaitState& state, JointStroke front, JointStroke rear, AxleRule::Kind kind,
                  double front_factor, double rear_factor) {
  EXPECT_EQ(state.front, front);
  EXPECT_EQ(state.rear, rear);
  EXPECT_EQ(state.rule.kind, kind);
  if (kind == AxleRule::Kind::kFixed) {
    EXPECT_EQ(state.rule.fixed.front, front_factor);
    EXPECT_EQ(state.rule.fixed.rear, rear_factor);
  } else {
    EXPECT_EQ(state.rule.epsilon, front_factor);
  }
}

// docs/design.md "Wheel-walking gaits", state by state (ε-rules list ε in the first factor).
TEST(GaitTable, TablesFollowTheSpec) {
  using enum AxleRule::Kind;
  const auto rolking = gait_states(Gait::kRolking);
  ASSERT_EQ(rolking.size(), 2u);
  expect_state(rolking[0], kContracted, kExtended, kEpsilonFormula, 0.5, 0.0);
  expect_state(rolking[1], kExtended, kContracted, kFixed, 1.0, 1.0);
  const auto front = gait_states(Gait::kFrontWheelWalking);
  ASSERT_EQ(front.size(), 2u);
  expect_state(front[0], kContracted, kHeld, kFixed, 0.0, 0.0);
  expect_state(front[1], kExtended, kHeld, kFixed, 1.0, 0.0);
  const auto rear = gait_states(Gait::kRearWheelWalking);
  ASSERT_EQ(rear.size(), 2u);
  expect_state(rear[0], kHeld, kContracted, kFixed, 0.0, 1.0);
  expect_state(rear[1], kHeld, kExtended, kFixed, 0.0, 0.0);
  const auto worm = gait_states(Gait::kWormLike);
  ASSERT_EQ(worm.size(), 2u);
  expect_state(worm[0], kContracted, kContracted, kFixed, 0.0, 1.0);
  expect_state(worm[1], kExtended, kExtended, kFixed, 1.0, 0.0);
  const auto extended = gait_states(Gait::kRolkingExtendedBase);
  ASSERT_EQ(extended.size(), 2u);
  expect_state(extended[0], kMidStroke, kExtended, kEpsilonFormula, 0.5, 0.0);
  expect_state(extended[1], kExtended, kMidStroke, kFixed, 1.0, 1.0);
  EXPECT_TRUE(gait_states(Gait::kNone).empty());
}

// Backward swaps front and rear: strokes, fixed factors, ε → 1 − ε; twice is the identity.
TEST(GaitTable, BackwardMirrorsFrontAndRear) {
  const GaitState front_step = gait_state(Gait::kFrontWheelWalking, 1, DrivingIntent::kBackward);
  EXPECT_EQ(front_step.front, kHeld);
  EXPECT_EQ(front_step.rear, kExtended);
  EXPECT_EQ(front_step.rule.fixed.front, 0.0);
  EXPECT_EQ(front_step.rule.fixed.rear, 1.0);
  GaitState skewed{kMidStroke, kContracted, {AxleRule::Kind::kEpsilonFormula, {}, 0.2}};
  EXPECT_DOUBLE_EQ(mirrored(skewed).rule.epsilon, 0.8);
  for (const Gait gait : kGaits) {
    for (std::size_t i = 0; i < gait_states(gait).size(); ++i) {
      const GaitState forward = gait_state(gait, i, DrivingIntent::kForward);
      const GaitState twice = mirrored(mirrored(forward));
      EXPECT_EQ(twice.front, forward.front);
      EXPECT_EQ(twice.rear, forward.rear);
      EXPECT_EQ(twice.rule.fixed.front, forward.rule.fixed.front);
      EXPECT_EQ(twice.rule.epsilon, forward.rule.epsilon);
    }
  }
  EXPECT_THROW(gait_state(Gait::kRolking, 2, DrivingIntent::kForward), std::out_of_range);
  EXPECT_THROW(gait_state(Gait::kNone, 0, DrivingIntent::kForward), std::out_of_range);
}

// C = ∓acos(a/b) = ∓1.212062 lies 3.8e-5 outside JointParams' rounded ∓1.2121 and is clamped
// to it; E = ∓2.55; M = ∓(1.212062 + 2.55)/2 = ∓1.881031.
TEST(GaitTable, StrokePositionsLieInTheJointBounds) {
  const JointParams joints;
  const StrokePositions front = front_stroke_positions(GeometryParams{}, GaitParams{}, joints);
  const StrokePositions rear = rear_stroke_positions(GeometryParams{}, GaitParams{}, joints);
  EXPECT_EQ(front.contracted_rad, -1.2121);
  EXPECT_EQ(front.extended_rad, -2.55);
  EXPECT_NEAR(front.mid_stroke_rad, -1.881031, 1e-6);
  EXPECT_EQ(rear.contracted_rad, 1.2121);
  EXPECT_EQ(rear.extended_rad, 2.55);
  EXPECT_NEAR(rear.mid_stroke_rad, 1.881031, 1e-6);
  EXPECT_EQ(stroke_target_rad(kHeld, front, -1.7), -1.7);
  EXPECT_EQ(stroke_target_rad(kMidStroke, front, -1.7), front.mid_stroke_rad);
  GaitParams beyond;
  beyond.extended_rad = 3.0;
  EXPECT_EQ(rear_stroke_positions(GeometryParams{}, beyond, joints).extended_rad, 2.55);
}

// Each transition moves the axles as docs/design.md describes, and over one cycle all three axles
// advance by the same distance: forward for ϱ = 0, backward for ϱ = 1. Transitions are driven
// at constant rates with both joints synchronised; y = −Δcf and +Δcr (motor sign), the center
// axle rolls at yf + yr − q (axle_placement.hpp). One stroke C ↔ E is Δc = c(2.55) − c(1.2121)
// = 0.539453 − 0.386715 = 0.152738 m (worm-like: two strokes per cycle); M ↔ E is
// c(2.55) − c(1.881031) = 0.539453 − 0.477659 = 0.061794 m.
TEST(GaitTable, EveryGaitAdvancesInTheIntendedDirection) {
  const GeometryParams geometry;
  const JointParams joints;
  const StrokePositions front = front_stroke_positions(geometry, GaitParams{}, joints);
  const StrokePositions rear = rear_stroke_positions(geometry, GaitParams{}, joints);
  const double held_front = -1.6;
  const double held_rear = 1.9;
  for (const Gait gait : kGaits) {
    for (const DrivingIntent intent : {DrivingIntent::kForward, DrivingIntent::kBackward}) {
      const std::size_t count = gait_states(gait).size();
      std::array<double, 3> travel{};  // front, center, rear axle [m]
      for (std::size_t k = 0; k < count; ++k) {
        const GaitState from = gait_state(gait, (k + count - 1) % count, intent);
        const GaitState to = gait_state(gait, k, intent);
        const double p6_from = stroke_target_rad(from.front, front, held_front);
        const double p6_to = stroke_target_rad(to.front, front, held_front);
        const double p7_from = stroke_target_rad(from.rear, rear, held_rear);
        const double p7_to = stroke_target_rad(to.rear, rear, held_rear);
        const AxleDistanceRates rates{
            -(front_lever(p6_to, geometry).clearance_m -
              front_lever(p6_from, geometry).clearance_m),
            rear_lever(p7_to, geometry).clearance_m - rear_lever(p7_from, geometry).clearance_m};
        const AxleFactors factors = to.rule.kind == AxleRule::Kind::kFixed
                                        ? to.rule.fixed
                                        : two_joint_axle_factors(rates, to.rule.epsilon);
        const ExteriorAxleVelocities axles = exterior_axle_velocities(rates, factors);
        const double q = factors.front * rates.front_mps + factors.rear * rates.rear_mps;
        travel[0] += axles.front_mps;
        travel[1] += rates.front_mps + rates.rear_mps - q;
        travel[2] += axles.rear_mps;
      }
      const double sign = intent == DrivingIntent::kForward ? 1.0 : -1.0;
      const double expected = gait == Gait::kWormLike              ? 2 * 0.152738
                              : gait == Gait::kRolkingExtendedBase ? 0.061794
                                                                   : 0.152738;
      for (const double distance : travel) {
        EXPECT_NEAR(distance, sign * expected, 1e-6) << gait_name(gait) << " " << sign;
      }
    }
  }
}

// Rolking's first transition (C,E) → (E,C) with ρf = ρr = 1: the exterior axles advance by one
// stroke, the center stays.
TEST(GaitTable, RolkingKeepsTheCenterThenTheExteriorAxles) {
  const double stroke = 0.152738;
  const ExteriorAxleVelocities out = exterior_axle_velocities({-stroke, -stroke}, {1.0, 1.0});
  EXPECT_NEAR(out.front_mps, stroke, 1e-15);
  EXPECT_NEAR(out.rear_mps, stroke, 1e-15);
  const AxleFactors back = two_joint_axle_factors({stroke, stroke}, 0.5);
  const ExteriorAxleVelocities in = exterior_axle_velocities({stroke, stroke}, back);
  EXPECT_NEAR(in.front_mps, 0.0, 1e-15);
  EXPECT_NEAR(in.rear_mps, 0.0, 1e-15);
}

TEST(GaitTable, NamesAndValidation) {
  EXPECT_EQ(gait_name(Gait::kWormLike), "worm-like");
  EXPECT_EQ(gait_name(Gait::kRolkingExtendedBase), "rolking with extended base");
  GaitParams short_stroke;
  short_stroke.extended_rad = 1.0;
  expect_invalid_argument([&] { validate(short_stroke, GeometryParams{}); },
                          {"extended_rad", "acos(a/b)"});
  GaitParams too_fast;
  too_fast.max_joint_speed_fraction = 1.5;
  expect_invalid_argument([&] { validate(too_fast, GeometryParams{}); },
                          {"max_joint_speed_fraction"});
  GaitParams nan_stroke;
  nan_stroke.extended_rad = kNaN;
  expect_invalid_argument([&] { validate(nan_stroke, GeometryParams{}); }, {"extended_rad"});
  expect_invalid_argument([] { stroke_target_rad(kHeld, StrokePositions{}, kNaN); },
                          {"held_position_rad"});
}

}  // namespace
}  // namespace marsokhod::mobility
