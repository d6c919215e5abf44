#include "sim/electrics/battery.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace marsokhod::sim {
namespace {

BatteryTruth full_pair() {
  BatteryTruth truth;
  truth.initial_state_of_charge = 1.0;
  return truth;
}

TEST(SimBattery, OpenCircuitVoltageAndResistanceFollowTheCharge) {
  Battery battery(full_pair());
  EXPECT_NEAR(battery.open_circuit_voltage_v(), 2.0 * 12.75, 1e-12);
  EXPECT_NEAR(battery.internal_resistance_ohm(), 0.15, 1e-12);
  battery.set_state_of_charge(0.0);
  EXPECT_NEAR(battery.open_circuit_voltage_v(), 23.6, 1e-12);
  EXPECT_NEAR(battery.internal_resistance_ohm(), 0.30, 1e-12);
  battery.set_state_of_charge(0.5);
  EXPECT_NEAR(battery.internal_resistance_ohm(), 0.15 + 0.15 * 0.25, 1e-12);
}

TEST(SimBattery, VoltageSagsWithLoadAndRecovers) {
  Battery battery(full_pair());
  const double rest_v = battery.step(1.05, 0.001);
  // A 5 A load: at once I·R, then the polarisation adds up to I·R_p = 0.3 V over 5 s.
  const double loaded_now_v = battery.step(6.05, 0.001);
  EXPECT_NEAR(rest_v - loaded_now_v, 5.0 * 0.15, 0.01);
  double loaded_v = loaded_now_v;
  for (int i = 0; i < 30000; ++i) {
    loaded_v = battery.step(6.05, 0.001);
  }
  EXPECT_LT(loaded_v, loaded_now_v - 0.25);  // 30 s ≫ τ_p: most of 0.3 V more
  const double released_v = battery.step(1.05, 0.001);
  EXPECT_GT(released_v, loaded_v + 0.7);  // the I·R part returns at once
  double recovered_v = released_v;
  for (int i = 0; i < 30000; ++i) {
    recovered_v = battery.step(1.05, 0.001);
  }
  EXPECT_GT(recovered_v, released_v + 0.25);  // and the polarisation decays
  EXPECT_LT(recovered_v, rest_v);             // minus the charge drawn
}

TEST(SimBattery, ChargeIntegratesTheCurrent) {
  Battery battery(full_pair());
  // 1 A for an hour from 5 Ah: 20 % of the charge.
  for (int i = 0; i < 3600; ++i) {
    battery.step(1.0, 1.0);
  }
  EXPECT_NEAR(battery.state_of_charge(), 0.8, 1e-9);
}

TEST(SimBattery, SagFaultAddsSeriesResistance) {
  Battery battery(full_pair());
  const double healthy_v = battery.terminal_voltage_v(5.0);
  battery.set_extra_resistance_ohm(1.0);
  EXPECT_NEAR(healthy_v - battery.terminal_voltage_v(5.0), 5.0, 1e-12);
  EXPECT_THROW(battery.set_extra_resistance_ohm(-1.0), std::invalid_argument);
  EXPECT_THROW(battery.set_state_of_charge(1.5), std::invalid_argument);
}

TEST(SimBattery, RejectsImpossibleParameters) {
  BatteryTruth truth;
  truth.capacity_ah = 0.0;
  EXPECT_THROW(Battery{truth}, std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::sim
