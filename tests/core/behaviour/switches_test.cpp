#include "core/behaviour/switches.hpp"

#include <gtest/gtest.h>

namespace marsokhod::behaviour {
namespace {

// The defaults of params.hpp: the four joint and power behaviours on, load distribution off.
TEST(BehaviourSwitches, DefaultParamsSwitchOnAllButLoadDistribution) {
  const BehaviourSwitches switches =
      switches_from_params(BehaviourParams{}, LoadDistributionParams{});
  EXPECT_TRUE(switches.power_management);
  EXPECT_TRUE(switches.slant_response);
  EXPECT_TRUE(switches.contract_on_turn);
  EXPECT_TRUE(switches.axle_placement);
  EXPECT_EQ(switches.load_distribution, LoadDistributionMode::kOff);
}

TEST(BehaviourSwitches, CopiesEachConfiguredSwitch) {
  BehaviourParams behaviours;
  behaviours.power_management = false;
  behaviours.axle_placement = false;
  LoadDistributionParams load_distribution;
  load_distribution.mode = LoadDistributionMode::kSlip;
  const BehaviourSwitches switches = switches_from_params(behaviours, load_distribution);
  EXPECT_FALSE(switches.power_management);
  EXPECT_TRUE(switches.slant_response);
  EXPECT_TRUE(switches.contract_on_turn);
  EXPECT_FALSE(switches.axle_placement);
  EXPECT_EQ(switches.load_distribution, LoadDistributionMode::kSlip);
}

TEST(BehaviourSwitches, AllSwitchedOff) {
  const BehaviourSwitches switches = all_switched_off();
  EXPECT_FALSE(switches.power_management);
  EXPECT_FALSE(switches.slant_response);
  EXPECT_FALSE(switches.contract_on_turn);
  EXPECT_FALSE(switches.axle_placement);
  EXPECT_EQ(switches.load_distribution, LoadDistributionMode::kOff);
}

}  // namespace
}  // namespace marsokhod::behaviour
