#include "core/behaviour/axle_placement.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "behaviour_test_support.hpp"

namespace marsokhod::behaviour {
namespace {

using test::invalid_argument_message;
using test::kNaN;
using ::testing::HasSubstr;

// h = 1/64 s, exact in binary, so f moves by exactly 1/64 per fast cycle at the default rate
// 1/s. Defaults: load threshold 0.5 rad/s, speed threshold 0.1 rad/s.
constexpr double kPeriodS = 1.0 / 64.0;

AxlePlacementStep step(const AxlePlacementState& state, double requested, double load_radps,
                       double velocity_radps,
                       const BehaviourSwitches& switches = BehaviourSwitches{},
                       const AxleResistance& axles = AxleResistance{}) {
  return next_axle_placement(state, requested, load_radps, velocity_radps, axles, kPeriodS,
                             BehaviourParams{}, switches);
}

// Unswitched, the requested ρ passes through unchanged, also when it changes every cycle.
TEST(AxlePlacement, UnloadedJointPassesTheRequestedPlacement) {
  AxlePlacementStep result = step(AxlePlacementState{}, 0.3, 0.1, 0.5);
  EXPECT_EQ(result.placement, 0.3);
  result = step(result.state, 0.7, -0.2, 0.8);
  EXPECT_EQ(result.placement, 0.7);
  EXPECT_FALSE(result.state.switched);
  EXPECT_EQ(result.state.switch_fraction, 0.0);
}

// Chapter 6.2.3's illustration, front-wheel walking C → E with ρf = 1 while the front axle
// cannot advance. The front joint extends: p6 falls, w < 0, ν < 0, l = w − ν.
//   blocked:       w = −0.02, ν = −0.82, l = +0.8 > 0.5  → switch at once (slow): ρ = 0.
//   freed, slow:   w = −0.05, ν = −0.35, l = +0.3        → still driven: hold, ρ = 0.
//   bending:       w = −0.40, ν = −0.45, l = +0.05       → fast: hold, ρ = 0.
//   at its target: w = −0.05, ν = −0.07, l = +0.02       → stopped, not driven: ρ = 1.
TEST(AxlePlacement, BlockedJointBacksTheRoverUpUntilTheBendingEnds) {
  AxlePlacementStep result = step(AxlePlacementState{}, 1.0, 0.8, -0.02);
  EXPECT_TRUE(result.state.switched);
  EXPECT_EQ(result.placement, 0.0);
  result = step(result.state, 1.0, 0.3, -0.05);
  EXPECT_TRUE(result.state.switched);
  EXPECT_EQ(result.placement, 0.0);
  result = step(result.state, 1.0, 0.05, -0.4);
  EXPECT_TRUE(result.state.switched);
  EXPECT_EQ(result.placement, 0.0);
  result = step(result.state, 1.0, 0.02, -0.05);
  EXPECT_FALSE(result.state.switched);
  EXPECT_EQ(result.placement, 1.0);
}

// A joint loaded while fast moves ρ gradually: f = k/64 after k cycles, so ρ = 1 − k/64:
// 0.984375 after one cycle, 0.5 after 32, 0 after 64; never faster than rate · h = 1/64.
TEST(AxlePlacement, FastJointSwitchesGradually) {
  AxlePlacementStep result = step(AxlePlacementState{}, 1.0, 0.8, 0.5);
  EXPECT_EQ(result.placement, 0.984375);
  double previous = result.placement;
  for (int k = 2; k <= 80; ++k) {
    result = step(result.state, 1.0, 0.8, 0.5);
    EXPECT_LE(std::abs(result.placement - previous), kPeriodS + 1e-15);
    previous = result.placement;
    if (k == 32) {
      EXPECT_EQ(result.placement, 0.5);
    }
  }
  EXPECT_EQ(result.placement, 0.0);
  EXPECT_EQ(result.state.switch_fraction, 1.0);
}

// Half-way engaged (16 fast cycles: f = 0.25, ρ = 0.75), then the joint stops undriven: the
// switch ends and, the joint being slow, ρ returns at once to 1.
TEST(AxlePlacement, ReleaseWhenStoppedReturnsAtOnce) {
  AxlePlacementStep result{AxlePlacementState{}, 1.0};
  for (int k = 0; k < 16; ++k) {
    result = step(result.state, 1.0, 0.8, 0.5);
  }
  EXPECT_EQ(result.placement, 0.75);
  result = step(result.state, 1.0, 0.0, 0.0);
  EXPECT_FALSE(result.state.switched);
  EXPECT_EQ(result.placement, 1.0);
}

// A state handed in unswitched with f = 0.5 while the joint is fast returns gradually:
// f = 0.5 − 1/64 = 0.484375, ρ = (1 − f) · 0.2 + f · 0.8 = 0.2 + 0.6 f = 0.490625.
TEST(AxlePlacement, FastJointReturnsGradually) {
  const AxlePlacementStep result = step(AxlePlacementState{false, 0.5}, 0.2, 0.0, 0.5);
  EXPECT_EQ(result.state.switch_fraction, 0.484375);
  EXPECT_NEAR(result.placement, 0.490625, 1e-15);
}

// Switched and loaded again (the rover cannot back up either): the switch holds, no toggling.
TEST(AxlePlacement, LoadedAgainWhileSwitchedHolds) {
  AxlePlacementStep result = step(AxlePlacementState{}, 0.0, -0.8, 0.0);
  EXPECT_EQ(result.placement, 1.0);
  for (int k = 0; k < 10; ++k) {
    result = step(result.state, 0.0, -0.9, 0.01);
    EXPECT_TRUE(result.state.switched);
    EXPECT_EQ(result.placement, 1.0);
  }
}

// ρ = 0.5 is its own mirror: the switch changes nothing.
TEST(AxlePlacement, HalfPlacementIsItsOwnMirror) {
  EXPECT_EQ(step(AxlePlacementState{}, 0.5, 0.9, 0.0).placement, 0.5);
}

// An axle's resistance is how much slower than driven its wheels turn, −sgn(ν) · l, once both
// have stopped though driven (|ν| ≥ 0.1, |w| = |l + ν| < 0.1 rad/s); the smaller of the two.
TEST(AxlePlacement, AnAxlesResistanceIsHowMuchSlowerThanDrivenItsStoppedWheelsTurn) {
  const BehaviourParams params;
  // Forward: driven at 0.62, turning at 0.05: l = −0.57 on both wheels.
  EXPECT_DOUBLE_EQ(axle_resistance_radps(-0.57, 0.62, -0.57, 0.62, params), 0.57);
  // Backward: driven at −0.5, turning at −0.05: l = +0.45; the other wheel at 0.02 (l = +0.52).
  EXPECT_DOUBLE_EQ(axle_resistance_radps(0.45, -0.5, 0.52, -0.5, params), 0.45);
  // One wheel stopped (w = 0.02), the other turning at 0.5: the axle moves, 0.
  EXPECT_EQ(axle_resistance_radps(-0.6, 0.62, -0.12, 0.62, params), 0.0);
  // Both lagging their drive of 1.1 by 0.51 but turning at 0.59 (a stroke's start): 0.
  EXPECT_EQ(axle_resistance_radps(-0.51, 1.1, -0.51, 1.1, params), 0.0);
  // Stopped but driven at 0.05, under the speed threshold: not driven, 0.
  EXPECT_EQ(axle_resistance_radps(-0.05, 0.05, -0.05, 0.05, params), 0.0);
}

// Front-wheel walking's contraction with ρf = 0 (the centre and rear advance, the front axle
// stands) while the centre wheels stand at a block's face: the front axle gives way instead,
// so the joint turns at half its command (w = 0.3, ν = 0.6, l = −0.3, under the 0.5 threshold),
// while the centre wheels, driven at 0.62, turn at 0.05 (resistance 0.57 > 0.5). After the hold
// time, 0.5 s = 32 cycles of 1/64 s, ρ switches; the joint is fast, so ρ moves gradually:
// f = 1/64 in the first switched cycle, ρ = 1/64.
AxlePlacementStep hold(AxlePlacementStep result, int cycles, double requested,
                       const AxleResistance& axles) {
  for (int k = 0; k < cycles; ++k) {
    result = step(result.state, requested, -0.3, 0.3, {}, axles);
  }
  return result;
}

TEST(AxlePlacement, TheMovingAxleStoppedWhileTheJointTurnsSwitchesAfterTheHoldTime) {
  const AxleResistance centre_held{0.0, 0.57};
  AxlePlacementStep result = hold({AxlePlacementState{}, 0.0}, 31, 0.0, centre_held);
  EXPECT_FALSE(result.state.switched);
  EXPECT_EQ(result.placement, 0.0);
  EXPECT_EQ(result.state.held_s, 31.0 / 64.0);
  result = hold(result, 1, 0.0, centre_held);
  EXPECT_TRUE(result.state.switched);
  EXPECT_EQ(result.placement, 0.015625);
  EXPECT_EQ(result.state.held_s, 0.0);
}

// A stroke's start stops the moving axle for a few cycles: a cycle in which it turns again
// starts the hold time afresh (20 + 1 + 31 cycles: not switched; one more: switched).
TEST(AxlePlacement, AnAxleThatTurnsAgainStartsTheHoldTimeAfresh) {
  const AxleResistance centre_held{0.0, 0.57};
  AxlePlacementStep result = hold({AxlePlacementState{}, 0.0}, 20, 0.0, centre_held);
  result = hold(result, 1, 0.0, AxleResistance{});
  EXPECT_EQ(result.state.held_s, 0.0);
  result = hold(result, 31, 0.0, centre_held);
  EXPECT_FALSE(result.state.switched);
  result = hold(result, 1, 0.0, centre_held);
  EXPECT_TRUE(result.state.switched);
}

// Only the axle ρ moves counts: at ρ = 0 the exterior axle stands as an anchor, at ρ = 1 the
// centre does. And a lag of exactly the threshold is not more than it.
TEST(AxlePlacement, OnlyTheAxleThePlacementMovesCounts) {
  const AxleResistance exterior_held{0.57, 0.0};
  const AxleResistance centre_held{0.0, 0.57};
  EXPECT_FALSE(hold({AxlePlacementState{}, 0.0}, 64, 0.0, exterior_held).state.switched);
  EXPECT_TRUE(hold({AxlePlacementState{}, 1.0}, 32, 1.0, exterior_held).state.switched);
  EXPECT_FALSE(hold({AxlePlacementState{}, 1.0}, 64, 1.0, centre_held).state.switched);
  EXPECT_FALSE(
      hold({AxlePlacementState{}, 0.0}, 64, 0.0, AxleResistance{0.0, 0.5}).state.switched);
}

// A joint that is not driven (|ν| = |w − l| < 0.1) is not bending: wheels held back then are
// driving into something, which is (4.16)'s and the operator's business, not the placement's.
TEST(AxlePlacement, HeldWheelsOfAJointNotDrivenDoNotSwitch) {
  AxlePlacementStep result{AxlePlacementState{}, 0.0};
  for (int k = 0; k < 64; ++k) {
    result = step(result.state, 0.0, 0.02, 0.05, {}, AxleResistance{0.0, 0.9});
  }
  EXPECT_FALSE(result.state.switched);
  EXPECT_EQ(result.state.held_s, 0.0);
  EXPECT_EQ(result.placement, 0.0);
}

// Switched off: ρ as requested, and the state is reset so that switching on starts clean.
TEST(AxlePlacement, SwitchedOffPassesTheRequestAndResets) {
  const AxlePlacementStep result =
      step(AxlePlacementState{true, 1.0}, 1.0, 0.9, 0.0, all_switched_off());
  EXPECT_EQ(result.placement, 1.0);
  EXPECT_FALSE(result.state.switched);
  EXPECT_EQ(result.state.switch_fraction, 0.0);
}

TEST(AxlePlacement, RejectsInvalidInputsByName) {
  EXPECT_THAT(invalid_argument_message([] { step(AxlePlacementState{}, 1.2, 0.0, 0.0); }),
              HasSubstr("next_axle_placement: requested_placement = 1.2"));
  EXPECT_THAT(invalid_argument_message([] { step(AxlePlacementState{}, 0.5, kNaN, 0.0); }),
              HasSubstr("joint_load_radps = nan"));
  EXPECT_THAT(invalid_argument_message([] {
                step(AxlePlacementState{false, 2.0}, 0.5, 0, 0);
              }),
              HasSubstr("state.switch_fraction = 2"));
  EXPECT_THAT(invalid_argument_message([] {
                step(AxlePlacementState{false, 0.0, -1.0}, 0.5, 0, 0);
              }),
              HasSubstr("state.held_s = -1"));
  EXPECT_THAT(invalid_argument_message([] {
                next_axle_placement({}, 0.5, 0.0, 0.0, {}, 0.0, BehaviourParams{},
                                    BehaviourSwitches{});
              }),
              HasSubstr("period_s = 0"));
  BehaviourParams params;
  params.axle_placement_rate_per_s = 0.0;
  EXPECT_THAT(invalid_argument_message([&] {
                next_axle_placement({}, 0.5, 0.0, 0.0, {}, kPeriodS, params, BehaviourSwitches{});
              }),
              HasSubstr("params.axle_placement_rate_per_s = 0"));
  EXPECT_THAT(invalid_argument_message([] {
                step(AxlePlacementState{}, 0.5, 0.0, 0.0, {}, AxleResistance{0.0, kNaN});
              }),
              HasSubstr("axles.interior_radps = nan"));
  EXPECT_THAT(invalid_argument_message([] {
                axle_resistance_radps(0.0, kNaN, 0.0, 0.0, BehaviourParams{});
              }),
              HasSubstr("axle_resistance_radps: left_drive_radps = nan"));
}

}  // namespace
}  // namespace marsokhod::behaviour
