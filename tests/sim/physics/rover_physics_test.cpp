// The rover physics as the rest of the simulator uses it: drive, step, the joints through their
// backlash and lock, faults, determinism. Every scenario counts exact steps of 1 ms.
#include "sim/physics/rover_physics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "physics_test_support.hpp"
#include "sim/physics/chassis_geometry.hpp"

namespace marsokhod::sim {
namespace {

using testing::all_wheels;
using testing::drive_at;
using testing::expect_healthy;
using testing::joints_only;
using testing::run;

TEST(RoverPhysics, StartsAtRestOnTheShaftsInitialPositions) {
  RoverPhysics physics(Params{}, TerrainSpec{});
  EXPECT_DOUBLE_EQ(physics.timestep_s(), 0.001);
  EXPECT_DOUBLE_EQ(physics.time_s(), 0.0);
  // Remark 3.1's joints, each shaft at its gap's upper end (p + b) so that Procedure 4.3's push
  // toward the negative end crosses the whole gap first.
  const MotorVector shaft = physics.shaft_angle_rad();
  EXPECT_DOUBLE_EQ(shaft[kFrontJoint], -1.2121 + 0.052);
  EXPECT_DOUBLE_EQ(shaft[kRearJoint], 1.2121 + 0.250);
  EXPECT_DOUBLE_EQ(physics.truth().joint_angle_rad[kFrontJoint], -1.2121);
  EXPECT_DOUBLE_EQ(physics.truth().joint_angle_rad[kRearJoint], 1.2121);
  run(physics, 500);
  EXPECT_NEAR(physics.time_s(), 0.5, 1e-12);
  // Unpowered, the rover settles and stays put: the joints hold on their locks.
  EXPECT_NEAR(physics.truth().joint_angle_rad[kFrontJoint], -1.2121, 1e-3);
  EXPECT_NEAR(physics.truth().joint_angle_rad[kRearJoint], 1.2121, 1e-3);
  EXPECT_NEAR(physics.truth().position_m[0], 0.0, 1e-3);
  expect_healthy(physics);
}

TEST(RoverPhysics, RejectsADriveOffTheSpeedTorqueLine) {
  RoverPhysics physics(Params{}, TerrainSpec{});
  MotorDrive drive = drive_at(all_wheels(1.0));
  drive.droop_radps_per_nm[3] = 0.0;
  EXPECT_THROW(physics.set_drive(drive), std::invalid_argument);
  drive = drive_at(all_wheels(1.0));
  drive.no_load_speed_radps[7] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(physics.set_drive(drive), std::invalid_argument);
  drive = drive_at(all_wheels(1.0), -1.0);
  EXPECT_THROW(physics.set_drive(drive), std::invalid_argument);
}

TEST(RoverPhysics, RejectsAnInitialJointBeyondItsStops) {
  Params params;
  params.motors.initial_position_rad[kRearJoint] = 3.0;
  EXPECT_THROW(RoverPhysics(params, TerrainSpec{}), std::invalid_argument);
}

TEST(RoverPhysics, WheelTorqueFollowsTheSpeedTorqueLine) {
  RoverPhysics physics(Params{}, TerrainSpec{});
  run(physics, 300);
  physics.set_drive(drive_at(all_wheels(2.0)));
  physics.step();
  // Standing wheels: τ = (ω0 − 0)/droop, below stall.
  EXPECT_NEAR(physics.shaft_torque_nm()[kCenterLeft], 2.0 / testing::kDroopRadpsPerNm, 0.5);
  physics.set_drive(drive_at(all_wheels(2.0), 10.0));
  physics.step();
  EXPECT_NEAR(physics.shaft_torque_nm()[kCenterLeft], 10.0, 1e-9);  // clipped at stall
  run(physics, 1500);
  // Cruising on hard ground: hardly any load, so the wheels turn at ω0 − droop·τ ≈ ω0.
  const MotorVector speed = physics.shaft_velocity_radps();
  const MotorVector torque = physics.shaft_torque_nm();
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    EXPECT_NEAR(speed[wheel], 2.0 - testing::kDroopRadpsPerNm * torque[wheel], 1e-3) << wheel;
    EXPECT_NEAR(speed[wheel], 2.0, 0.01) << wheel;
  }
  expect_healthy(physics);
}

// A load that drives a wheel makes its motor generate, and a generating motor's braking grows with
// the overspeed, not bounded by the duty's τ_stall (5 N·m at d = 0). On the stand, a weight of peak
// 20 N·m strapped to a wheel at d = 0 (ω0 = 0, B = 0.045 rad/s per N·m, the low-duty droop) comes
// down on the line at most 20·B = 0.9 rad/s when the brake may grow with the speed, τ_stall +
// |ω|/B, up to the full-duty stall torque (40 N·m); bounded at τ_stall (brake 0), the weight
// swings down with only 5 N·m against it, ten times faster (10.2 rad/s).
TEST(RoverPhysics, AWheelItsLoadDrivesBrakesOnItsLineBeyondTheStallTorque) {
  const auto peak_speed = [](double brake_nm) {
    RoverPhysics physics(Params{}, TerrainSpec{});
    physics.place_on_stand(0.0, 0.0);
    physics.set_drive(drive_at(all_wheels(0.5), 100.0));  // the weight 0.3 rad off the top
    run(physics, 600);
    EXPECT_NEAR(physics.shaft_angle_rad()[kFrontLeft], 0.3, 0.05);
    physics.strap_weight(kFrontLeft, 20.0);
    MotorDrive idle = drive_at(all_wheels(0.0), 5.0);
    idle.droop_radps_per_nm.fill(0.045);
    idle.brake_torque_nm.fill(brake_nm);
    double fastest = 0.0;
    for (int step = 0; step < 4000; ++step) {
      physics.set_drive(idle);
      physics.step();
      fastest = std::max(fastest, std::abs(physics.shaft_velocity_radps()[kFrontLeft]));
    }
    EXPECT_GT(physics.shaft_angle_rad()[kFrontLeft], 1.5);  // it came down
    expect_healthy(physics);
    return fastest;
  };
  const double braked = peak_speed(40.0);
  const double on_stall_alone = peak_speed(0.0);
  EXPECT_LT(braked, 20.0 * 0.045 * 1.05);
  EXPECT_GT(braked, 20.0 * 0.045 * 0.8);
  EXPECT_GT(on_stall_alone, 3.0 * braked);
}

// Plugging: a wheel driven forward (ω0 = 0.5 rad/s, τ_stall 5 N·m, B = 0.045) but turned back by a
// heavier load (a strapped weight of peak 8 N·m, from 1.2 rad behind the top) adds its back-EMF to
// the bridge's voltage: its torque along d grows from τ_stall by |ω|/B, continuously, so the weight
// comes down at most (8 − 5)·B = 0.135 rad/s. (Its line, (ω0 + |ω|)/B, would give 11 N·m and more:
// the bound, not the line, holds it.)
TEST(RoverPhysics, AWheelTurnedAgainstItsDutyResistsWithTheStallTorquePlusItsSpeedOverB) {
  RoverPhysics physics(Params{}, TerrainSpec{});
  physics.place_on_stand(0.0, 0.0);
  physics.set_drive(drive_at(all_wheels(-0.5), 100.0));  // the weight 1.2 rad behind the top
  run(physics, 2400);
  physics.set_drive(drive_at(all_wheels(0.0), 100.0));  // and held there
  run(physics, 300);
  EXPECT_NEAR(physics.shaft_angle_rad()[kFrontLeft], -1.2, 0.05);
  physics.strap_weight(kFrontLeft, 8.0);
  MotorDrive forward = drive_at(all_wheels(0.5), 5.0);
  forward.droop_radps_per_nm.fill(0.045);
  forward.brake_torque_nm.fill(40.0);
  double fastest_back = 0.0;
  for (int step = 0; step < 6000; ++step) {
    physics.set_drive(forward);
    physics.step();
    fastest_back = std::max(fastest_back, -physics.shaft_velocity_radps()[kFrontLeft]);
  }
  EXPECT_LT(physics.shaft_angle_rad()[kFrontLeft], -1.8);  // it came down, backwards
  EXPECT_NEAR(fastest_back, 3.0 * 0.045, 0.1 * 3.0 * 0.045);
  expect_healthy(physics);
}

// Shaft travel from the start until the joint has moved by 1 mrad, the shaft turning at `speed`.
double shaft_travel_before_joint_moves(RoverPhysics& physics, std::size_t motor,
                                       double speed_radps) {
  MotorVector speeds{};
  speeds[motor] = speed_radps;
  physics.set_drive(drive_at(speeds));
  const double shaft_start = physics.shaft_angle_rad()[motor];
  const double joint_start = physics.truth().joint_angle_rad[motor];
  for (int step = 0; step < 3000; ++step) {
    physics.step();
    if (std::abs(physics.truth().joint_angle_rad[motor] - joint_start) > 1e-3) {
      return std::abs(physics.shaft_angle_rad()[motor] - shaft_start);
    }
  }
  return std::numeric_limits<double>::infinity();
}

// Procedure 4.1's backlash: 14° at the rear joint. The shaft starts at the gap's upper end, so
// extending (+) moves the joint at once; contracting first crosses the whole gap, and so does
// every reversal after.
TEST(RoverPhysics, RearJointMovesOnlyAfterTheShaftCrossesTheGap) {
  RoverPhysics physics(Params{}, TerrainSpec{});
  physics.set_drive(drive_at({}));
  run(physics, 300);
  EXPECT_LT(shaft_travel_before_joint_moves(physics, kRearJoint, 2.0), 0.01);
  run(physics, 200);
  // 1 mrad of joint motion at 2 rad/s of shaft adds about 1 mrad and a few steps of lag.
  EXPECT_NEAR(shaft_travel_before_joint_moves(physics, kRearJoint, -2.0), 0.250, 0.01);
  run(physics, 200);
  EXPECT_NEAR(shaft_travel_before_joint_moves(physics, kRearJoint, 2.0), 0.250, 0.01);
  expect_healthy(physics);
}

TEST(RoverPhysics, FrontJointBacklashIsThreeDegrees) {
  RoverPhysics physics(Params{}, TerrainSpec{});
  physics.set_drive(drive_at({}));
  run(physics, 300);
  // p6 = −γf: extending is negative, first across the gap from its upper end.
  EXPECT_NEAR(shaft_travel_before_joint_moves(physics, kFrontJoint, -2.0), 0.052, 0.01);
  run(physics, 200);
  EXPECT_NEAR(shaft_travel_before_joint_moves(physics, kFrontJoint, 2.0), 0.052, 0.01);
  expect_healthy(physics);
}

// Figure 3.3: "the central unit is tilted by ½(αf − αr)". Extending the front joint on flat
// ground lowers the front strut to αf(γf) and the center unit follows half way, nose down.
TEST(RoverPhysics, ExtendingTheFrontJointLengthensTheBaseAndTiltsTheCenterUnit) {
  const Params params;
  RoverPhysics physics(params, TerrainSpec{});
  physics.set_drive(drive_at({}));
  run(physics, 300);
  const GroundTruth before = physics.truth();
  MotorVector speeds{};
  speeds[kFrontJoint] = -2.0;
  physics.set_drive(joints_only(speeds));
  run(physics, 500);
  physics.set_drive(drive_at({}));
  run(physics, 500);
  const GroundTruth after = physics.truth();
  const double front_bend = -after.joint_angle_rad[kFrontJoint];
  const double rear_bend = after.joint_angle_rad[kRearJoint];
  EXPECT_GT(front_bend, 1.8);
  const auto base_m = [](const GroundTruth& truth) {
    return truth.wheel_position_m[kFrontLeft][0] - truth.wheel_position_m[kBackLeft][0];
  };
  EXPECT_NEAR(base_m(after) - base_m(before),
              axle_distance_m(params.geometry, front_bend) -
                  axle_distance_m(params.geometry, vertical_bend_rad(params.geometry)),
              5e-3);
  const double tilt_rad = 0.5 * (strut_elevation_rad(params.geometry, front_bend) -
                                 strut_elevation_rad(params.geometry, rear_bend));
  EXPECT_NEAR(after.roll_pitch_yaw_rad[1], -tilt_rad, 3e-3);  // nose down: positive about y
  EXPECT_GT(after.roll_pitch_yaw_rad[1], 0.01);
  expect_healthy(physics);
}

// Chapter 5.3's lock: with the joint motors idle, driving the rover loads the joints and they
// keep their angles.
TEST(RoverPhysics, IdleJointsHoldUnderLoad) {
  RoverPhysics physics(Params{}, TerrainSpec{});
  MotorVector speeds{};
  speeds[kFrontJoint] = -2.0;
  speeds[kRearJoint] = 2.0;
  physics.set_drive(joints_only(speeds));
  run(physics, 600);  // both levers well extended: their weight and the ground bend them
  physics.set_drive(drive_at(all_wheels(2.0)));
  run(physics, 50);
  const MotorVector held = physics.truth().joint_angle_rad;
  EXPECT_LT(held[kFrontJoint], -1.5);
  EXPECT_GT(held[kRearJoint], 1.5);
  run(physics, 2000);
  EXPECT_NEAR(physics.truth().joint_angle_rad[kFrontJoint], held[kFrontJoint], 2e-3);
  EXPECT_NEAR(physics.truth().joint_angle_rad[kRearJoint], held[kRearJoint], 2e-3);
  EXPECT_GT(physics.truth().position_m[0], 0.3);  // it did drive
  expect_healthy(physics);
}

// A load stronger than the motor stalls the joint; the lock never lets it be driven back. Driving
// forward on a ground with rolling friction (C_rr ≈ 0.16, 0.02 m), the rear wheels push the rear
// axle toward the center unit against the rolling resistance (≈ 6 N·m about the rear joint),
// against extending it; the rear joint's motor, limited to 0.5 N·m, crosses the gap, bears on the
// joint and stalls.
TEST(RoverPhysics, AWeakMotorStallsButIsNeverBackDriven) {
  TerrainSpec terrain;
  terrain.ground = Material{0.5, 0.0, 0.02};
  RoverPhysics physics(Params{}, terrain);
  physics.set_drive(drive_at({}));
  run(physics, 300);
  const double start_rad = physics.truth().joint_angle_rad[kRearJoint];
  MotorVector speeds = all_wheels(2.0);
  speeds[kRearJoint] = 2.0;
  MotorDrive drive = drive_at(speeds);
  drive.stall_torque_nm[kRearJoint] = 0.5;
  physics.set_drive(drive);
  for (int step = 0; step < 3000; ++step) {
    physics.step();
    ASSERT_GE(physics.truth().joint_angle_rad[kRearJoint], start_rad - 2e-3) << step;
  }
  // The shaft has crossed the gap and pushes at its stall torque, standing still.
  EXPECT_NEAR(physics.shaft_angle_rad()[kRearJoint] - physics.truth().joint_angle_rad[kRearJoint],
              0.250, 5e-3);
  EXPECT_NEAR(physics.shaft_torque_nm()[kRearJoint], 0.5, 1e-9);
  EXPECT_NEAR(physics.shaft_velocity_radps()[kRearJoint], 0.0, 1e-2);
  EXPECT_GT(physics.truth().position_m[0], 0.4);  // while the rover drove on
  expect_healthy(physics);
}

// The lock while pushing (chapter 5.3): a load that aids the motor cannot drive the joint ahead of
// it. Extending the front joint with the wheels rolling free, the rover's weight swings the lever
// down; with a soft speed–torque line (droop 0.3 rad/s per N·m) that aiding load would run the
// shaft far beyond ω0 = 0.3 rad/s. The joint advances at ω0 and the motor itself bears ≈ no load.
TEST(RoverPhysics, AnAidingLoadNeverDrivesAJointAheadOfItsMotor) {
  RoverPhysics physics(Params{}, TerrainSpec{});
  physics.set_drive(drive_at({}));
  run(physics, 300);
  MotorVector speeds{};
  speeds[kFrontJoint] = -0.3;
  MotorDrive drive = joints_only(speeds);
  drive.droop_radps_per_nm[kFrontJoint] = 0.3;
  physics.set_drive(drive);
  const double start_rad = physics.truth().joint_angle_rad[kFrontJoint];
  double previous_rad = start_rad;
  for (int step = 0; step < 3000; ++step) {
    physics.step();
    const double joint_rad = physics.truth().joint_angle_rad[kFrontJoint];
    ASSERT_GE((joint_rad - previous_rad) / physics.timestep_s(), -0.3 - 0.01) << step;
    previous_rad = joint_rad;
  }
  EXPECT_LT(physics.truth().joint_angle_rad[kFrontJoint], start_rad - 0.5);  // it did extend
  EXPECT_NEAR(physics.shaft_torque_nm()[kFrontJoint], 0.0, 0.1);
  expect_healthy(physics);
}

TEST(RoverPhysics, ABlockedWheelStallsItsMotor) {
  RoverPhysics physics(Params{}, TerrainSpec{});
  run(physics, 300);
  physics.set_wheel_blocked(kCenterLeft, true);
  const double angle = physics.shaft_angle_rad()[kCenterLeft];
  physics.set_drive(drive_at(all_wheels(1.0)));
  run(physics, 1000);
  EXPECT_NEAR(physics.shaft_angle_rad()[kCenterLeft], angle, 0.01);
  EXPECT_NEAR(physics.shaft_torque_nm()[kCenterLeft], 1.0 / testing::kDroopRadpsPerNm, 1.0);
  physics.set_wheel_blocked(kCenterLeft, false);
  run(physics, 1000);
  EXPECT_NEAR(physics.shaft_velocity_radps()[kCenterLeft], 1.0, 0.05);
  EXPECT_THROW(physics.set_wheel_blocked(6, true), std::out_of_range);
  expect_healthy(physics);
}

// A jammed joint (the joint-blocked failsafe's scenario): commanded to extend, the front joint
// and its motor's shaft stay where the jam caught them, the motor stalled against it; released,
// the joint extends again.
TEST(RoverPhysics, AJammedJointHoldsAgainstItsMotor) {
  RoverPhysics physics(Params{}, TerrainSpec{});
  physics.set_drive(drive_at({}));
  run(physics, 300);
  physics.set_joint_jammed(0, true);
  const double joint = physics.truth().joint_angle_rad[kFrontJoint];
  const double shaft = physics.shaft_angle_rad()[kFrontJoint];
  MotorVector speeds{};
  speeds[kFrontJoint] = -2.0;
  physics.set_drive(joints_only(speeds));
  run(physics, 1000);
  EXPECT_NEAR(physics.truth().joint_angle_rad[kFrontJoint], joint, 1e-3);
  EXPECT_NEAR(physics.shaft_angle_rad()[kFrontJoint], shaft, 1e-3);
  EXPECT_NEAR(physics.shaft_velocity_radps()[kFrontJoint], 0.0, 1e-3);
  physics.set_joint_jammed(0, false);
  run(physics, 500);
  EXPECT_LT(physics.truth().joint_angle_rad[kFrontJoint], joint - 0.1);  // extending
  EXPECT_THROW(physics.set_joint_jammed(2, true), std::out_of_range);
  expect_healthy(physics);
}

TEST(RoverPhysics, AWheelWithoutContactSpinsFree) {
  RoverPhysics physics(Params{}, TerrainSpec{});
  physics.set_wheel_contact(kFrontRight, false);
  run(physics, 500);
  const GroundTruth truth = physics.truth();
  EXPECT_FALSE(truth.wheel_contact[kFrontRight]);
  EXPECT_TRUE(truth.wheel_contact[kFrontLeft]);
  EXPECT_THROW(physics.set_wheel_contact(9, false), std::out_of_range);
  expect_healthy(physics);
}

TEST(RoverPhysics, TwoRunsAreBitIdentical) {
  const auto record = [] {
    RoverPhysics physics(Params{}, testing::slope_deg(5.0));
    MotorVector speeds = all_wheels(1.5);
    speeds[kCenterLeft] = 0.5;
    speeds[kRearJoint] = 1.0;
    physics.set_drive(drive_at(speeds));
    run(physics, 1500);
    return std::make_pair(physics.truth(), physics.imu());
  };
  const auto [first, first_imu] = record();
  const auto [second, second_imu] = record();
  EXPECT_EQ(first.position_m, second.position_m);
  EXPECT_EQ(first.roll_pitch_yaw_rad, second.roll_pitch_yaw_rad);
  EXPECT_EQ(first.velocity_mps, second.velocity_mps);
  EXPECT_EQ(first.joint_angle_rad, second.joint_angle_rad);
  EXPECT_EQ(first.wheel_slip_mps, second.wheel_slip_mps);
  EXPECT_EQ(first_imu.accel_mps2, second_imu.accel_mps2);
}

// Set down from the stand with the joints bent (Procedure 5.1 sets them there), the exterior
// axles hang below the centre one: every wheel comes down clear of the ground and the lowest
// 5 mm above it, and the rover settles upright. (Placed by the centre axle's height, the exterior
// wheels started 0.2 m into the ground; on soft sand the rover was thrown onto its back.)
TEST(RoverPhysics, SetDownFromTheStandWithBentJointsEveryWheelClearsTheGround) {
  for (const bool soft : {false, true}) {
    SCOPED_TRACE(soft ? "soft sand" : "hard ground");
    TerrainSpec terrain;
    if (soft) terrain.ground = sand();
    RoverPhysics physics(Params{}, terrain);
    physics.place_on_stand(0.0, 0.0);
    MotorVector bend{};
    bend[kFrontJoint] = -1.0;
    bend[kRearJoint] = 1.0;
    physics.set_drive(drive_at(bend));
    run(physics, 600);
    physics.set_drive(drive_at(MotorVector{}));
    const double radius = Params{}.geometry.wheel_radius_m;
    physics.place_on_ground();
    const GroundTruth placed = physics.truth();
    double lowest = 1.0, highest = 0.0;
    for (const auto& wheel : placed.wheel_position_m) {
      lowest = std::min(lowest, wheel[2] - radius);
      highest = std::max(highest, wheel[2] - radius);
    }
    EXPECT_NEAR(lowest, 0.005, 1e-6);
    EXPECT_GT(highest - lowest, 0.05);  // the joints are bent: the axles stand at other heights
    run(physics, 2000);
    expect_healthy(physics);
    EXPECT_LT(std::abs(physics.truth().roll_pitch_yaw_rad[0]), 0.1);
    EXPECT_LT(std::abs(physics.truth().roll_pitch_yaw_rad[1]), 0.1);
  }
}

// Procedure 3.4's hand: at 1 rad/s and 1 ms steps the front axle is at exactly 0.2 rad after 200
// steps, then held at 0.3; the rear, asked beyond its stop, rests on it at −0.524 rad.
TEST(RoverPhysics, ProcedureThreeFoursHandTurnsAnAxleAndHoldsIt) {
  RoverPhysics physics(Params{}, TerrainSpec{});
  physics.place_on_stand(0.0, 0.0);
  run(physics, 50);
  const double rear_start = physics.imu().rear_tilt_rad;
  physics.hold_axle_tilt(0, 0.3);
  physics.hold_axle_tilt(1, -1.0);
  const double front_start = physics.imu().front_tilt_rad;
  run(physics, 200);
  EXPECT_NEAR(physics.imu().front_tilt_rad, front_start + 0.2, 1e-9);
  EXPECT_NEAR(physics.imu().rear_tilt_rad, rear_start - 0.2, 1e-9);
  run(physics, 600);
  EXPECT_NEAR(physics.imu().front_tilt_rad, 0.3, 1e-12);
  EXPECT_NEAR(physics.imu().rear_tilt_rad, -kMaxAxleTiltRad, 1e-12);
  expect_healthy(physics);
  EXPECT_THROW(physics.hold_axle_tilt(2, 0.0), std::out_of_range);
  EXPECT_THROW(physics.hold_axle_tilt(0, std::nan("")), std::invalid_argument);
  physics.hold_axle_tilt(0, std::nullopt);  // let go: the axle is free again
  physics.hold_axle_tilt(1, std::nullopt);
  run(physics, 10);
  expect_healthy(physics);
}

}  // namespace
}  // namespace marsokhod::sim
