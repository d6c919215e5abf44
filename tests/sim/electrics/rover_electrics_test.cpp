#include "sim/electrics/rover_electrics.hpp"

#include <gtest/gtest.h>

namespace marsokhod::sim {
namespace {

SimTruth full_battery_truth() {
  SimTruth truth = exact_sim_truth(Params{});
  truth.power.battery.initial_state_of_charge = 1.0;
  return truth;
}

// Six wheels at duty d with torque τ and speed ω; joints idle.
ElectricsInput driving(double duty, double torque_nm, double speed_radps) {
  ElectricsInput input;
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    input.duty[i] = duty;
    input.shaft_torque_nm[i] = torque_nm;
    input.shaft_speed_radps[i] = speed_radps;
  }
  return input;
}

TEST(RoverElectrics, RestingRoverDrawsTheBaseLoad) {
  RoverElectrics electrics(full_battery_truth());
  const ElectricsOutput& output = electrics.step(ElectricsInput{}, 0.001);
  // Chapter 3.1: 0.69 + 0.13 + 0.23 A.
  EXPECT_NEAR(output.total_current_a, 1.05, 1e-12);
  EXPECT_NEAR(output.supply_v, 25.5 - 1.05 * 0.15, 0.001);
  EXPECT_TRUE(output.computer_on);
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    EXPECT_EQ(output.drive.no_load_speed_radps[i], 0.0);
  }
}

TEST(RoverElectrics, DutyDrivesTheNoLoadSpeedsThroughTheLag) {
  RoverElectrics electrics(full_battery_truth());
  ElectricsInput input = driving(0.5, 0.0, 0.0);
  for (int i = 0; i < 200; ++i) {
    electrics.step(input, 0.001);
  }
  const ElectricsOutput& output = electrics.output();
  const MotorTruth& front_left = electrics.motor(kFrontLeft).truth();
  EXPECT_NEAR(output.drive.no_load_speed_radps[kFrontLeft],
              steady_no_load_speed_radps(front_left, 0.5, output.supply_v, 511), 1e-3);
  EXPECT_EQ(output.drive.no_load_speed_radps[kFrontJoint], 0.0);
  EXPECT_EQ(output.drive.stall_torque_nm[kFrontJoint], 5.0);
}

TEST(RoverElectrics, HeavyDrivingSagsTheBatteryAndItRecovers) {
  RoverElectrics electrics(full_battery_truth());
  const double rest_v = electrics.step(ElectricsInput{}, 0.001).supply_v;
  // Six wheels at d = 0.9 pushing 5 N·m at 2.3 rad/s: 6·(0.12 + 0.06·2.3 + 0.9·5/7.5) = 5.148 A
  // more than the base load's 1.05 A (chapter 3.1: heavy driving "might exceed 5 A").
  electrics.step(driving(0.9, 5.0, 2.3), 0.001);  // the duty now in force
  const ElectricsOutput& loaded = electrics.step(driving(0.9, 5.0, 2.3), 0.001);
  EXPECT_NEAR(loaded.total_current_a, 6.198, 1e-9);
  EXPECT_LT(loaded.supply_v, rest_v - 0.75);  // 5.148 A·0.15 Ω = 0.77 V at once
  const double loaded_a = loaded.total_current_a;
  for (int i = 0; i < 2; ++i) {
    electrics.step(ElectricsInput{}, 0.001);
  }
  EXPECT_NEAR(electrics.output().supply_v, rest_v, 0.01);
  // Back to the base load, while the peak keeps the loaded step's current (what a scenario's
  // max_supply_current_a reports).
  EXPECT_NEAR(electrics.output().total_current_a, 1.05, 1e-12);
  EXPECT_EQ(electrics.output().peak_total_current_a, loaded_a);
}

TEST(RoverElectrics, SagFaultBrownsTheComputerOut) {
  RoverElectrics electrics(full_battery_truth());
  electrics.set_extra_series_resistance_ohm(1.2);
  electrics.step(driving(0.9, 5.0, 2.3), 0.001);
  // About 6 A through 1.35 Ω: 25.5 − 8.1 V < 19.5 V.
  const ElectricsOutput& output = electrics.step(driving(0.9, 5.0, 2.3), 0.001);
  EXPECT_LT(output.supply_v, 19.5);
  EXPECT_FALSE(output.computer_on);
  EXPECT_EQ(output.brownout_count, 1U);
  // The computer's 0.69 A dropped out of the base load.
  EXPECT_NEAR(electrics.step(ElectricsInput{}, 0.001).base_load_a, 0.36, 1e-12);
}

TEST(RoverElectrics, ForcedBrownoutAndLowCharge) {
  RoverElectrics electrics(full_battery_truth());
  electrics.force_brownout();
  EXPECT_FALSE(electrics.output().computer_on);
  EXPECT_NEAR(electrics.output().reboot_remaining_s, 30.0, 1e-12);
  electrics.set_state_of_charge(0.1);
  EXPECT_NEAR(electrics.step(ElectricsInput{}, 0.001).state_of_charge, 0.1, 1e-6);
}

TEST(RoverElectrics, TetherSupplyLimitsTheCurrent) {
  SimTruth truth = full_battery_truth();
  truth.power.supply = SupplyKind::kTether;
  RoverElectrics electrics(truth);
  EXPECT_NEAR(electrics.step(ElectricsInput{}, 0.001).supply_v, 24.0 - 0.105, 1e-12);
  electrics.step(driving(1.0, 8.0, 1.0), 0.001);
  // 6·(0.12 + 0.06 + 8/7.5) + 1.05 = 8.53 A: 2.53 A over the limit folds back 10.1 V.
  EXPECT_LT(electrics.step(driving(1.0, 8.0, 1.0), 0.001).supply_v, 19.5);
}

TEST(RoverElectrics, SeededRunIsIdenticalTwice) {
  const SimTruth truth = make_sim_truth(Params{}, 5);
  RoverElectrics a(truth);
  RoverElectrics b(truth);
  for (int i = 0; i < 500; ++i) {
    const ElectricsInput input = driving(0.001 * i, 0.01 * i, 0.002 * i);
    const ElectricsOutput& out_a = a.step(input, 0.001);
    const ElectricsOutput& out_b = b.step(input, 0.001);
    ASSERT_EQ(out_a.supply_v, out_b.supply_v);
    ASSERT_EQ(out_a.drive.no_load_speed_radps, out_b.drive.no_load_speed_radps);
  }
}

}  // namespace
}  // namespace marsokhod::sim
