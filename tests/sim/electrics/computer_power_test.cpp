#include "sim/electrics/computer_power.hpp"

#include <gtest/gtest.h>

namespace marsokhod::sim {
namespace {

TEST(SimComputerPower, BrownsOutBelowTheThresholdAndRebootsAfterItsTime) {
  ComputerPower computer(19.5, 30.0);
  EXPECT_TRUE(computer.update(19.5, 0.5));  // at the threshold: still on
  EXPECT_FALSE(computer.update(19.4, 0.5));
  EXPECT_EQ(computer.brownout_count(), 1U);
  // 59 half seconds of steady supply are 29.5 s: still booting; the 60th completes 30 s.
  for (int i = 0; i < 59; ++i) {
    EXPECT_FALSE(computer.update(24.0, 0.5)) << i;
  }
  EXPECT_TRUE(computer.update(24.0, 0.5));
  EXPECT_EQ(computer.brownout_count(), 1U);
}

TEST(SimComputerPower, RebootStartsOverWhileTheSupplyStaysLow) {
  ComputerPower computer(19.5, 30.0);
  computer.update(19.0, 0.5);
  for (int i = 0; i < 50; ++i) {
    computer.update(24.0, 0.5);
  }
  computer.update(19.0, 0.5);  // another dip during the boot
  EXPECT_NEAR(computer.off_remaining_s(), 30.0, 1e-12);
  EXPECT_EQ(computer.brownout_count(), 1U);  // one brown-out: it never came up in between
}

TEST(SimComputerPower, ForcedBrownout) {
  ComputerPower computer(19.5, 2.0);
  computer.force_brownout();
  EXPECT_FALSE(computer.on());
  EXPECT_EQ(computer.brownout_count(), 1U);
  EXPECT_FALSE(computer.update(24.0, 1.0));
  EXPECT_TRUE(computer.update(24.0, 1.0));
  EXPECT_THROW(ComputerPower(19.5, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::sim
