// Everything the thesis' status window shows (Figure 8.1) and what our driver adds: the driver's
// output besides the CAN requests, published every cycle to the console, logs and scenarios.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/estimation/failsafes.hpp"
#include "core/estimation/pose_estimator.hpp"
#include "core/mobility/gait_table.hpp"
#include "core/navigation/mission.hpp"
#include "core/params.hpp"
#include "driver/frame_intake.hpp"
#include "driver/operator_commands.hpp"
#include "driver/startup.hpp"

namespace marsokhod::driver {

enum class DriverMode : std::uint8_t {
  kStartup,      // configuring the controllers, µ8's switch, Procedure 4.3
  kDriving,      // normal operation (also while stopped by the operator or the timeout)
  kCalibration,  // the operator's calibration mode (Remark 5.7)
  kFault,        // a latched fault stopped the rover
};
const char* mode_name(DriverMode mode);

struct MotorStatus {
  double shaft_position_rad = 0.0;  // p̄ (chapter 3.2)
  double position_rad = 0.0;        // p, after backlash (4.1)
  double position_uncertainty_rad = 0.0;  // how far p̄ may be off (motor_position.hpp)
  double velocity_radps = 0.0;      // w (4.2)
  double no_load_velocity_radps = 0.0;  // ν (4.4)
  double load_radps = 0.0;          // l = w − ν (Definition 4.9)
  double torque_nm = 0.0;           // τ = l/B±_icr(d) of (4.6), the external torque's estimate
  double commanded_radps = 0.0;     // ŵ of (5.4) after κ and h
  double slope_hold_radps = 0.0;    // the slope hold's share of ŵ (core/behaviour/slope_hold.hpp)
  double duty = 0.0;                // d sent this cycle
  int silent_cycles = 0;            // consecutive cycles without a response
};

struct JointBoundsStatus {
  double front_min_rad = 0.0, front_max_rad = 0.0, rear_min_rad = 0.0, rear_max_rad = 0.0;
};

struct TargetStatus {
  double v1_radps = 0.0, v2_radps = 0.0, v3_radps = 0.0, v4_radps = 0.0, v6_radps = 0.0,
         v7_radps = 0.0;
};

struct DriverStatus {
  double mission_time_s = 0.0;
  double cycle_time_s = 0.0;       // since the previous step
  std::uint64_t cycle = 0;
  DriverMode mode = DriverMode::kStartup;
  StartupPhase startup_phase = StartupPhase::kConfigure;
  // Chapter 3.3.
  double supply_v = 0.0;
  double reference_supply_v = 0.0;  // Ū
  double yaw_rate_radps = 0.0;
  std::array<double, 3> accel_mps2{};
  double front_tilt_rad = 0.0, rear_tilt_rad = 0.0;
  double slope_rad = 0.0;           // σ, chapter 6.2.1
  std::array<MotorStatus, kMotorCount> motors{};
  int sensor_silent_cycles = 0;     // µ8
  // Chapters 5 and 6.
  double max_duty = 1.0;            // D of (6.3)
  // Field Experiment 1.1 (core/behaviour/supply_current.hpp): the supply's current the duties
  // sent this cycle could draw at most, every motor stalled (every supply), and the bound D_I on
  // D that keeps it within the tether's limit (1 on the battery; max_duty is the smaller of it
  // and (6.3)'s).
  double supply_current_bound_a = 0.0;
  double current_duty_bound = 1.0;
  double driving_scale = 1.0;       // κ of (5.5)
  double walking_scale = 1.0;
  TargetStatus targets;             // what the operator asks (after the timeout rule)
  TargetStatus commands;            // v1…v7 after (4.14)–(4.16) and the behaviours
  mobility::Gait gait = mobility::Gait::kNone;
  std::size_t gait_state = 0;
  double gait_speed = 0.0;
  double front_axle_factor = 0.0;   // ρf
  double rear_axle_factor = 0.0;    // ρr
  JointBoundsStatus joint_bounds;
  // Where the joints' positions come from: "Procedure 4.3", "calibration mode", "kept across a
  // restart (µ6 moved +0.0012 rad, µ7 0.0000 rad while down)" or "unknown: <why>"; while
  // joints_known is false the joints are held (driver.hpp).
  bool joints_known = true;
  std::string joint_origin;
  // Safety.
  bool operator_timeout = true;
  std::string operator_rejection;   // the latest invalid operator input's reason
  bool stop_latched = false;        // stopped; targets zero until a neutral input re-arms
  std::string stop_reason;          // the latest stop's origin ("client 3 pressed STOP")
  std::vector<std::string> faults;  // latched faults, e.g. "µ3 silent for 3 cycles"
  std::vector<std::string> warnings;  // not latched, e.g. "supply 19.8 V near brown-out"
  BusCounters bus;
  std::string lcd;                  // the 8 characters sent to µ8
  // Dead reckoning from the gyro and the centre wheels (core/estimation/pose_estimator.hpp), in
  // the odometry frame of where this driver's start-up ended.
  estimation::Pose pose;
  // The failsafes of core/estimation/failsafes.hpp: the chassis' attitude from the mean gravity
  // (+ left side up, + nose down), how long the wheels have been stalled, and how long each
  // joint (front, rear) has been stalled under its command.
  estimation::Attitude attitude;
  double stalled_s = 0.0;
  std::array<double, 2> joint_stalled_s{};
  // The operator's mission (core/navigation/mission.hpp): cmd_vel, turn, move, goto.
  navigation::MissionStatus mission;
  // The run-time settings in force this cycle (the operator's configure, a scenario's [runtime]).
  RuntimeSettings settings;
};

}  // namespace marsokhod::driver
