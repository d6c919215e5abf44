#include "sim/electrics/tether_supply.hpp"

#include <gtest/gtest.h>

namespace marsokhod::sim {
namespace {

TEST(SimTetherSupply, ConstantVoltageBehindTheCable) {
  const TetherSupply supply(TetherTruth{});
  EXPECT_NEAR(supply.terminal_voltage_v(0.0), 24.0, 1e-12);
  EXPECT_NEAR(supply.terminal_voltage_v(5.0), 24.0 - 0.5, 1e-12);
  EXPECT_FALSE(supply.current_limited(5.0));
}

TEST(SimTetherSupply, FoldsBackAboveTheCurrentLimit) {
  const TetherSupply supply(TetherTruth{});
  // 7 A: 24 − 0.7 − 4·(7 − 6) = 19.3 V, below the brown-out threshold.
  EXPECT_NEAR(supply.terminal_voltage_v(7.0), 19.3, 1e-12);
  EXPECT_TRUE(supply.current_limited(7.0));
  EXPECT_EQ(supply.terminal_voltage_v(100.0), 0.0);
}

TEST(SimTetherSupply, SagFaultAndValidation) {
  TetherSupply supply(TetherTruth{});
  supply.set_extra_resistance_ohm(0.5);
  EXPECT_NEAR(supply.terminal_voltage_v(2.0), 24.0 - 2.0 * 0.6, 1e-12);
  TetherTruth bad;
  bad.set_v = 31.0;
  EXPECT_THROW(TetherSupply{bad}, std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::sim
