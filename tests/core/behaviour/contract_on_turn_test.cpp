#include "core/behaviour/contract_on_turn.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "behaviour_test_support.hpp"

namespace marsokhod::behaviour {
namespace {

using test::invalid_argument_message;
using test::kNaN;
using ::testing::HasSubstr;

constexpr double kTolerance = 1e-12;
constexpr double kNoLoadSpeedRadps = 2.827;  // w
// Chosen so that v̄6 = 2.827/2 = 1.4135 rad/s and v̄7 = 2.827/2.827 = 1 rad/s.
constexpr double kMaxAbsN6 = 2.0;
constexpr double kMaxAbsN7 = 2.827;

JointVelocityTargets contract(const JointVelocityTargets& targets, double spin_radps,
                              const BehaviourSwitches& switches = BehaviourSwitches{}) {
  return contract_joints_when_turning(targets, spin_radps, kNoLoadSpeedRadps, kMaxAbsN6, kMaxAbsN7,
                                      switches);
}

// Joints at rest, v2ᵈ = ±0.5: v6ᵈ = 0 + 0.5, v7ᵈ = 0 − 0.5, whichever way the rover spins.
TEST(ContractOnTurn, SpinningContractsBothJoints) {
  for (const double spin_radps : {0.5, -0.5}) {
    const JointVelocityTargets targets = contract({0.0, 0.0}, spin_radps);
    EXPECT_NEAR(targets.front_radps, 0.5, kTolerance);
    EXPECT_NEAR(targets.rear_radps, -0.5, kTolerance);
  }
}

// The signs contract: p6 = −γf, so v6 > 0 lowers γf; p7 = +γr, so v7 < 0 lowers γr. One
// second from the extended pose (γf = γr = 2.0) with the targets above moves both levers
// toward acos(a/b) = 1.2121: γf = −(−2.0 + 0.5) = 1.5, γr = 2.0 − 0.5 = 1.5.
TEST(ContractOnTurn, ContractionMeansSmallerGamma) {
  const JointVelocityTargets targets = contract({0.0, 0.0}, 1.0 / 2.0);
  const double front_position_rad = -2.0 + targets.front_radps * 1.0;  // p6
  const double rear_position_rad = 2.0 + targets.rear_radps * 1.0;     // p7
  EXPECT_NEAR(-front_position_rad, 1.5, kTolerance);                   // γf
  EXPECT_NEAR(rear_position_rad, 1.5, kTolerance);                     // γr
}

// No spin: the operator's targets pass (inside the limits).
TEST(ContractOnTurn, NoSpinKeepsTheTargets) {
  const JointVelocityTargets targets = contract({0.2, -0.3}, 0.0);
  EXPECT_EQ(targets.front_radps, 0.2);
  EXPECT_EQ(targets.rear_radps, -0.3);
}

// An operator extending both joints (v6ᵈ = −0.8, v7ᵈ = +0.8) while spinning at 0.5: the
// extension slows to −0.3 and +0.3.
TEST(ContractOnTurn, TurningSlowsAnExtension) {
  const JointVelocityTargets targets = contract({-0.8, 0.8}, 0.5);
  EXPECT_NEAR(targets.front_radps, -0.3, kTolerance);
  EXPECT_NEAR(targets.rear_radps, 0.3, kTolerance);
}

// v2ᵈ = 3: 0 + 3 clips to v̄6 = 1.4135, 0 − 3 to −v̄7 = −1. Operator targets beyond the limits
// are clipped too: −2 → −1.4135, 2 − 0.5 = 1.5 → 1.
TEST(ContractOnTurn, ClipsToTheFeasibleJointSpeeds) {
  const JointVelocityTargets fast_spin = contract({0.0, 0.0}, 3.0);
  EXPECT_NEAR(fast_spin.front_radps, 1.4135, kTolerance);
  EXPECT_NEAR(fast_spin.rear_radps, -1.0, kTolerance);
  const JointVelocityTargets fast_operator = contract({-2.0, 2.0}, 0.5);
  EXPECT_NEAR(fast_operator.front_radps, -1.4135, kTolerance);
  EXPECT_NEAR(fast_operator.rear_radps, 1.0, kTolerance);
}

TEST(ContractOnTurn, SwitchedOffKeepsTheTargetsUnchanged) {
  const JointVelocityTargets targets = contract({-2.0, 0.4}, 3.0, all_switched_off());
  EXPECT_EQ(targets.front_radps, -2.0);
  EXPECT_EQ(targets.rear_radps, 0.4);
}

TEST(ContractOnTurn, RejectsInvalidInputsByName) {
  EXPECT_THAT(invalid_argument_message([] {
                contract({0.0, 0.0}, kNaN);
              }),
              HasSubstr("contract_joints_when_turning: spin_target_radps = nan"));
  EXPECT_THAT(invalid_argument_message([] {
                contract({0.0, kNaN}, 0.0);
              }),
              HasSubstr("targets.rear_radps = nan"));
  EXPECT_THAT(invalid_argument_message([] {
                contract_joints_when_turning({}, 0.0, kNoLoadSpeedRadps, 0.0, 1.0,
                                             BehaviourSwitches{});
              }),
              HasSubstr("max_abs_n6 = 0"));
  EXPECT_THAT(invalid_argument_message([] {
                contract_joints_when_turning({}, 0.0, -1.0, 1.0, 1.0, BehaviourSwitches{});
              }),
              HasSubstr("max_no_load_speed_radps = -1"));
}

}  // namespace
}  // namespace marsokhod::behaviour
