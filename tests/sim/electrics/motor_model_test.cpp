#include "sim/electrics/motor_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace marsokhod::sim {
namespace {

MotorTruth unit_motor() {
  MotorTruth motor;
  motor.scale = 1.0;  // W itself, as Procedure 4.4 measures it on the bench
  return motor;
}

TEST(SimMotorModel, TrueCurveHitsItsAnchorsAndDiffersFromTheTable) {
  const MotorTruth motor = unit_motor();
  EXPECT_NEAR(steady_no_load_speed_radps(motor, 0.3, 24.0, 511), 0.860, 1e-4);
  EXPECT_NEAR(steady_no_load_speed_radps(motor, 1.0, 24.0, 511), 2.800, 1e-4);
  // The driver's nominal W₅₁₁ table says 0.847 and 2.827: calibration has something to find.
  EXPECT_GT(std::abs(steady_no_load_speed_radps(motor, 0.3, 24.0, 511) - 0.847), 0.01);
  EXPECT_GT(std::abs(steady_no_load_speed_radps(motor, 1.0, 24.0, 511) - 2.827), 0.02);
}

TEST(SimMotorModel, SpeedRisesWithDutyAndVoltageAndIsOdd) {
  const MotorTruth motor = unit_motor();
  double previous = 0.0;
  for (int step = 1; step <= 20; ++step) {
    const double duty = 0.05 * step;
    const double speed = steady_no_load_speed_radps(motor, duty, 24.0, 511);
    EXPECT_GT(speed, previous) << "d = " << duty;
    previous = speed;
    EXPECT_EQ(steady_no_load_speed_radps(motor, -duty, 24.0, 511), -speed);
    EXPECT_GT(steady_no_load_speed_radps(motor, duty, 25.0, 511), speed);
    EXPECT_LT(steady_no_load_speed_radps(motor, duty, 21.0, 511), speed);
  }
}

TEST(SimMotorModel, DeadZoneHoldsTheShaftAtSmallDuty) {
  const MotorTruth motor = unit_motor();
  // U_dz = 1 V at icr 511: |d|·24 V must exceed it, d > 1/24 = 0.0417.
  EXPECT_EQ(steady_no_load_speed_radps(motor, 0.04, 24.0, 511), 0.0);
  EXPECT_GT(steady_no_load_speed_radps(motor, 0.05, 24.0, 511), 0.0);
  // Remark 3.2: a higher icr (lower frequency) lets the motor run slower: U_dz = 1·√(512/2048).
  EXPECT_NEAR(effective_voltage_v(motor, 0.04, 24.0, 2047), 0.96 - 0.5, 1e-12);
  EXPECT_GT(steady_no_load_speed_radps(motor, 0.04, 24.0, 2047), 0.0);
}

TEST(SimMotorModel, HigherIcrDrawsMoreCurrent) {
  const MotorTruth motor = unit_motor();
  // I0·(1 + 0.15·log2(2)) + I1·|ω| + |d|·|τ|/k_t = 0.12·1.15 + 0.06·1 + 0.5·3/7.5 at icr 1023.
  EXPECT_NEAR(motor_current_a(motor, 0.5, 1023, 3.0, 1.0), 0.138 + 0.06 + 0.2, 1e-12);
  EXPECT_NEAR(motor_current_a(motor, 0.5, 511, 3.0, 1.0), 0.12 + 0.06 + 0.2, 1e-12);
  EXPECT_EQ(motor_current_a(motor, 0.0, 511, 3.0, 1.0), 0.0);  // bridge off
}

TEST(SimMotorModel, TheSupplyFeedsTheMotorOnlyWhileTheBridgeConducts) {
  // A buck converter: the motor's current |τ|/k_t = 6/7.5 = 0.8 A flows from the supply a share
  // |d| of each period, U·I_supply = |d|·U·I_motor: 0.2 A of it at d = 0.25, all at d = 1.
  const MotorTruth motor = unit_motor();
  EXPECT_NEAR(motor_current_a(motor, 0.25, 511, 6.0, 0.0), 0.12 + 0.25 * 0.8, 1e-12);
  EXPECT_NEAR(motor_current_a(motor, 1.0, 511, 6.0, 0.0), 0.12 + 0.8, 1e-12);
  EXPECT_NEAR(motor_current_a(motor, -0.25, 511, -6.0, 0.0), 0.12 + 0.25 * 0.8, 1e-12);
}

TEST(SimMotorModel, GeneratingMotorDrawsOnlyItsLosses) {
  // The shaft driven along d faster than ω0 (τ·d < 0, a wheel braking the rover downhill or
  // dragged by the others): the torque's current returns through the diodes, the supply gives
  // I0 + I1·|ω| = 0.12 + 0.06·1.5 = 0.21 A, where a motoring torque of the same size adds
  // 0.6·4/7.5 = 0.32 A.
  const MotorTruth motor = unit_motor();
  EXPECT_NEAR(motor_current_a(motor, 0.6, 511, -4.0, 1.5), 0.21, 1e-12);
  EXPECT_NEAR(motor_current_a(motor, -0.6, 511, 4.0, -1.5), 0.21, 1e-12);
  EXPECT_NEAR(motor_current_a(motor, 0.6, 511, 4.0, 1.5), 0.21 + 0.6 * 4.0 / 7.5, 1e-12);
  EXPECT_NEAR(motor_current_a(motor, -0.6, 511, -4.0, -1.5), 0.21 + 0.6 * 4.0 / 7.5, 1e-12);
  // In the dead zone (ω0 = 0) the bridge holds a shaft turned along d by generating: losses
  // only; turned against d, it motors against the push.
  EXPECT_NEAR(motor_current_a(motor, 0.02, 511, -5.0, 0.5), 0.12 + 0.03, 1e-12);
  EXPECT_NEAR(motor_current_a(motor, 0.02, 511, 5.0, -0.5), 0.12 + 0.03 + 0.02 * 5.0 / 7.5, 1e-12);
}

TEST(SimMotorModel, HeavyDrivingDrawsMoreThanFiveAmperes) {
  // Chapter 3.1: "during heavy duty driving, the current flow might exceed 5 A". Six wheels at
  // d = 0.9 pushing 5 N·m at 2.3 rad/s: 6·(0.12 + 0.06·2.3 + 0.9·5/7.5) = 5.148 A, plus the base
  // load 1.05 A.
  const MotorTruth motor = unit_motor();
  const double total_a = 6.0 * motor_current_a(motor, 0.9, 511, 5.0, 2.3) + 1.05;
  EXPECT_NEAR(total_a, 6.198, 1e-9);
  EXPECT_GT(total_a, 5.0);
}

TEST(SimMotorModel, LagStepResponseIsFirstOrder) {
  const MotorTruth motor = unit_motor();
  MotorModel model(motor);
  const double steady = steady_no_load_speed_radps(motor, 0.5, 24.0, 511);
  for (int ms = 1; ms <= 12; ++ms) {
    model.step(0.5, 24.0, 511, 0.0, 0.001);
    EXPECT_NEAR(model.no_load_speed_radps(), steady * (1.0 - std::exp(-ms / 12.0)), 1e-12);
  }
  // One time constant: 63.2 % of the way.
  EXPECT_NEAR(model.no_load_speed_radps() / steady, 1.0 - std::exp(-1.0), 1e-12);
  // Exact discretisation: one 12 ms step lands on the same value.
  MotorModel coarse(motor);
  coarse.step(0.5, 24.0, 511, 0.0, 0.012);
  EXPECT_NEAR(coarse.no_load_speed_radps(), model.no_load_speed_radps(), 1e-12);
}

TEST(SimMotorModel, DroopDependsOnTheSignOfLoadTimesDuty) {
  const MotorTruth motor = unit_motor();
  MotorModel model(motor);
  for (int i = 0; i < 1000; ++i) {
    model.step(0.5, 24.0, 511, 0.0, 0.001);
  }
  const double no_load = model.no_load_speed_radps();
  // Braked below ω0 (τ·d < 0): B⁻; pushed beyond ω0 (τ·d ≥ 0): B⁺, as (4.7).
  EXPECT_EQ(model.step(0.5, 24.0, 511, no_load - 0.2, 0.001).droop_radps_per_nm, 0.015);
  EXPECT_EQ(model.step(0.5, 24.0, 511, no_load + 0.2, 0.001).droop_radps_per_nm, 0.030);
  // Figure 4.8: at small duty and high frequency the motor gives way more easily.
  EXPECT_NEAR(droop_radps_per_nm(motor, 0.15, 511, false), 0.015 * 1.25, 1e-15);
  EXPECT_NEAR(droop_radps_per_nm(motor, 0.15, 2047, false), 0.015 * 1.0625, 1e-15);
}

TEST(SimMotorModel, StallTorqueFollowsTheEffectiveVoltage) {
  const MotorTruth motor = unit_motor();
  EXPECT_NEAR(stall_torque_nm(motor, 1.0, 24.0, 511), 1.74 * 23.0, 1e-12);
  EXPECT_EQ(stall_torque_nm(motor, 0.0, 24.0, 511), 5.0);  // holding torque
  EXPECT_EQ(stall_torque_nm(motor, 0.1, 24.0, 511), 5.0);  // 1.74·1.4 V is below it
}

// A generating motor brakes up to the full-duty stall torque, the armature's U/R, whatever the
// duty: at d = 0 and 0.1 τ_stall is the 5 N·m holding torque, the brake 1.74·(24 − 1) N·m.
TEST(SimMotorModel, BrakeTorqueIsTheStallTorqueAtFullDutyWhateverTheDuty) {
  const MotorTruth motor = unit_motor();
  EXPECT_NEAR(brake_torque_nm(motor, 24.0, 511), 1.74 * 23.0, 1e-12);
  for (const double duty : {0.0, 0.1, -0.5, 1.0}) {
    MotorModel model(motor);
    const MotorLine line = model.step(duty, 24.0, 511, 0.0, 0.001);
    EXPECT_NEAR(line.brake_torque_nm, 1.74 * 23.0, 1e-12) << duty;
    EXPECT_LE(line.stall_torque_nm, line.brake_torque_nm) << duty;
  }
  MotorModel idle(motor);
  EXPECT_EQ(idle.step(0.0, 24.0, 511, 0.0, 0.001).stall_torque_nm, 5.0);
}

TEST(SimMotorModel, ZetaScalesTheSpeed) {
  MotorTruth motor = unit_motor();
  const double bench = steady_no_load_speed_radps(motor, 0.7, 24.0, 511);
  motor.scale = 0.941;
  EXPECT_NEAR(steady_no_load_speed_radps(motor, 0.7, 24.0, 511), 0.941 * bench, 1e-12);
}

}  // namespace
}  // namespace marsokhod::sim
