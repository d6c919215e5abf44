#include "runner/telemetry.hpp"

#include <cstdio>

namespace marsokhod::runner {
namespace {

constexpr const char* kPerMotor[] = {"shaft_rad", "p_rad",      "w_radps", "nu_radps",
                                     "load_radps", "tau_nm",    "cmd_radps", "hold_radps",
                                     "duty"};

void add(std::string& row, double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  if (!row.empty()) row += ',';
  row += text;
}

}  // namespace

std::string telemetry_header() {
  std::string h =
      "t_s,driver_running,mode,startup_phase,supply_v,reference_supply_v,yaw_rate_radps,"
      "accel1_mps2,accel2_mps2,accel3_mps2,front_tilt_rad,rear_tilt_rad,slope_rad,max_duty,"
      "driving_scale,walking_scale,target_v1,target_v2,target_v3,target_v4,target_v6,target_v7,"
      "cmd_v1,cmd_v2,cmd_v3,cmd_v4,cmd_v6,cmd_v7,gait,gait_state,gait_speed,rho_f,rho_r,front_min_rad,"
      "front_max_rad,rear_min_rad,rear_max_rad,operator_timeout,faults,malformed_frames,"
      "missed_responses";
  for (const char* motor : kMotorNames) {
    for (const char* q : kPerMotor) h += std::string(",") + motor + "_" + q;
  }
  h += ",true_x_m,true_y_m,true_z_m,true_roll_rad,true_pitch_rad,true_yaw_rad,true_speed_mps,"
       "true_yaw_rate_radps,true_p6_rad,true_p7_rad,true_supply_v,true_current_a,"
       "computer_on,energy_j";
  for (std::size_t w = 0; w < kWheelCount; ++w) h += std::string(",slip_") + kMotorNames[w] + "_mps";
  h += ",odo_x_m,odo_y_m,odo_heading_rad,odo_speed_mps,odo_distance_m,odo_sigma_m,"
       "odo_heading_sigma_rad,roll_rad,pitch_rad,stalled_s,supply_current_bound_a,current_duty_bound,"
       "front_joint_stalled_s,rear_joint_stalled_s";
  return h;
}

std::string telemetry_row(double time_s, bool running, const driver::DriverStatus& s,
                          const sim::SimulatedRover* rover) {
  std::string row;
  add(row, time_s);
  for (double v : {running ? 1.0 : 0.0, static_cast<double>(s.mode),
                   static_cast<double>(s.startup_phase), s.supply_v, s.reference_supply_v,
                   s.yaw_rate_radps, s.accel_mps2[0], s.accel_mps2[1], s.accel_mps2[2],
                   s.front_tilt_rad, s.rear_tilt_rad, s.slope_rad, s.max_duty, s.driving_scale,
                   s.walking_scale, s.targets.v1_radps, s.targets.v2_radps, s.targets.v3_radps,
                   s.targets.v4_radps, s.targets.v6_radps, s.targets.v7_radps,
                   s.commands.v1_radps, s.commands.v2_radps, s.commands.v3_radps,
                   s.commands.v4_radps, s.commands.v6_radps,
                   s.commands.v7_radps, static_cast<double>(s.gait),
                   static_cast<double>(s.gait_state), s.gait_speed, s.front_axle_factor,
                   s.rear_axle_factor, s.joint_bounds.front_min_rad, s.joint_bounds.front_max_rad,
                   s.joint_bounds.rear_min_rad, s.joint_bounds.rear_max_rad,
                   s.operator_timeout ? 1.0 : 0.0, static_cast<double>(s.faults.size()),
                   static_cast<double>(s.bus.malformed), static_cast<double>(s.bus.missed)}) {
    add(row, v);
  }
  for (const driver::MotorStatus& m : s.motors) {
    for (double v : {m.shaft_position_rad, m.position_rad, m.velocity_radps,
                     m.no_load_velocity_radps, m.load_radps, m.torque_nm, m.commanded_radps,
                     m.slope_hold_radps, m.duty}) {
      add(row, v);
    }
  }
  if (rover == nullptr) {
    row.append(14 + kWheelCount, ',');  // the truth's columns, empty
  } else {
    const sim::GroundTruth t = rover->truth();
    const auto& e = rover->electrics();
    for (double v : {t.position_m[0], t.position_m[1], t.position_m[2], t.roll_pitch_yaw_rad[0],
                     t.roll_pitch_yaw_rad[1], t.roll_pitch_yaw_rad[2],
                     std::hypot(t.velocity_mps[0], t.velocity_mps[1]), t.yaw_rate_radps,
                     t.joint_angle_rad[kFrontJoint], t.joint_angle_rad[kRearJoint], e.supply_v,
                     e.total_current_a, e.computer_on ? 1.0 : 0.0, rover->energy_used_j()}) {
      add(row, v);
    }
    for (double slip : t.wheel_slip_mps) add(row, slip);
  }
  const estimation::Pose& p = s.pose;
  for (double v : {p.x_m, p.y_m, p.heading_rad, p.speed_mps, p.distance_m, p.position_sigma_m(),
                   p.heading_sigma_rad(), s.attitude.roll_rad, s.attitude.pitch_rad, s.stalled_s,
                   s.supply_current_bound_a, s.current_duty_bound, s.joint_stalled_s[0],
                   s.joint_stalled_s[1]}) {
    add(row, v);
  }
  return row;
}

}  // namespace marsokhod::runner
