// Shared by the rover physics tests: drives, terrains and a runner counting exact steps.
#pragma once

#include <gtest/gtest.h>

#include <numbers>

#include "sim/physics/rover_physics.hpp"

namespace marsokhod::sim::testing {

// The Maxon RE 36 line at full supply: droop B⁺ = 0.030 rad/s per N·m (4.7), stall torque w/B.
inline constexpr double kDroopRadpsPerNm = 0.030;
inline constexpr double kStallTorqueNm = 2.827 / kDroopRadpsPerNm;

inline MotorDrive drive_at(const MotorVector& no_load_speed_radps,
                           double stall_torque_nm = kStallTorqueNm) {
  MotorDrive drive;
  drive.no_load_speed_radps = no_load_speed_radps;
  drive.droop_radps_per_nm.fill(kDroopRadpsPerNm);
  drive.stall_torque_nm.fill(stall_torque_nm);
  return drive;
}

// Only the joint motors powered; the wheels' H-bridges open (no torque), so that the wheels roll
// along as the levers swing instead of bracing against them.
inline MotorDrive joints_only(const MotorVector& no_load_speed_radps,
                              double stall_torque_nm = kStallTorqueNm) {
  MotorDrive drive = drive_at(no_load_speed_radps, stall_torque_nm);
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) drive.stall_torque_nm[wheel] = 0.0;
  return drive;
}

inline MotorVector all_wheels(double speed_radps) {
  return {speed_radps, speed_radps, speed_radps, speed_radps, speed_radps, speed_radps, 0.0, 0.0};
}

inline TerrainSpec slope_deg(double angle_deg) {
  TerrainSpec terrain;
  terrain.kind = TerrainKind::kSlope;
  terrain.slope_rad = angle_deg * std::numbers::pi / 180.0;
  return terrain;
}

inline void run(RoverPhysics& physics, int steps) {
  for (int i = 0; i < steps; ++i) physics.step();
}

// MuJoCo's own diagnosis: no instability, no overflowing contact buffer.
inline void expect_healthy(const RoverPhysics& physics) {
  EXPECT_EQ(physics.mujoco_warning_count(), 0);
}

}  // namespace marsokhod::sim::testing
