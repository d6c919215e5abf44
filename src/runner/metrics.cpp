#include "runner/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/mobility/lever_geometry.hpp"
#include "runner/soil_metrics.hpp"

namespace marsokhod::runner {
namespace {

constexpr double kStandstillRadps = 0.05;  // every shaft slower than this: standing
constexpr double kTimeEpsilonS = 1e-9;

double bound_excess(double p, double min, double max) {
  return std::max({0.0, min - p, p - max});
}

}  // namespace

const std::vector<std::string>& run_metric_names() {
  static const std::vector<std::string> names = {
      "distance_m", "forward_distance_m", "path_length_m", "yaw_change_rad", "climb_m",
      "mean_speed_mps", "max_voltage_drop_v", "min_supply_v", "max_abs_duty", "min_max_duty",
      "max_joint_bound_excess_rad", "final_front_joint_rad", "final_rear_joint_rad",
      "final_front_joint_max_rad", "final_rear_joint_min_rad", "final_joint_error_rad", "mean_abs_slip_mps", "max_slip_mps", "gait_state_changes",
      "operator_timeouts", "driver_faults", "malformed_frames", "brownouts", "max_supply_current_a",
      "driver_restarts",
      "energy_used_j", "final_max_abs_duty", "time_to_motors_off_s", "time_to_standstill_s",
      "odometry_position_error_m", "odometry_position_error_share", "odometry_heading_error_rad",
      "odometry_position_sigma_m", "wheel_odometry_position_error_m",
      "wheel_odometry_heading_error_rad", "max_roll_rad", "max_pitch_rad", "tip_over_faults",
      "stuck_faults", "joint_blocked_faults", "first_tip_over_s", "first_stuck_s",
      "first_joint_blocked_s", "max_joint_stall_s", "other_faults", "missions_started",
      "missions_reached", "missions_aborted", "mission_corrections", "final_mission_progress",
      "max_lateral_speed_mps", "max_lateral_drift_mps"};
  static const std::vector<std::string> with_soil = [] {
    std::vector<std::string> all = names;
    all.insert(all.end(), soil_metric_names().begin(), soil_metric_names().end());
    return all;
  }();
  return with_soil;
}

const std::vector<std::string>& phase_metric_names() {
  static const std::vector<std::string> names = {
      "duration_s", "distance_m", "forward_distance_m", "path_length_m", "mean_speed_mps",
      "yaw_change_rad", "yaw_rate_mean_radps", "climb_m", "energy_used_j", "mean_abs_slip_mps",
      "max_voltage_drop_v", "final_front_joint_rad", "final_rear_joint_rad",
      "final_joint_error_rad", "max_joint_error_rad", "max_joint_bound_excess_rad",
      "final_front_clearance_m", "final_rear_clearance_m", "min_front_joint_rad", "max_front_joint_rad", "min_rear_joint_rad", "max_rear_joint_rad",
      "gait_state_changes", "max_lateral_speed_mps", "max_lateral_drift_mps", "front_axle_forward_m", "rear_axle_forward_m",
      "mean_forward_m"};
  return names;
}

bool is_metric_name(const std::string& name, const std::vector<Phase>& phases) {
  const auto has = [](const std::vector<std::string>& names, const std::string& n) {
    return std::find(names.begin(), names.end(), n) != names.end();
  };
  if (has(run_metric_names(), name)) return true;
  const std::size_t dot = name.find('.');
  if (dot == std::string::npos) return false;
  const std::string phase = name.substr(0, dot);
  return std::any_of(phases.begin(), phases.end(), [&](const Phase& p) { return p.name == phase; }) &&
         has(phase_metric_names(), name.substr(dot + 1));
}

Metrics::Metrics(const Params& params, const std::vector<Phase>& phases) : params_(&params) {
  for (const Phase& p : phases) phases_.push_back({p, std::nullopt, std::nullopt, 0.0, 0.0});
}

void Metrics::mark_stop(double time_s) {
  if (!stop_mark_s_) stop_mark_s_ = time_s;
}

void Metrics::set_joint_targets(std::optional<double> front_rad, std::optional<double> rear_rad) {
  front_target_rad_ = front_rad;
  rear_target_rad_ = rear_rad;
}

double Metrics::joint_error_rad(const sim::GroundTruth& t) const {
  double error = 0.0;
  if (front_target_rad_) error = std::max(error, std::abs(t.joint_angle_rad[kFrontJoint] - *front_target_rad_));
  if (rear_target_rad_) error = std::max(error, std::abs(t.joint_angle_rad[kRearJoint] - *rear_target_rad_));
  return error;
}

Metrics::Snapshot Metrics::snapshot(const Session& session, double time_s) const {
  const sim::GroundTruth t = session.rover().truth();
  Snapshot s;
  s.time_s = time_s;
  s.position_m = last_position_m_;
  s.yaw_rad = yaw_unwrapped_rad_;
  s.path_length_m = path_length_m_;
  s.energy_j = session.rover().energy_used_j();
  s.slip_sum = slip_sum_;
  s.slip_samples = slip_samples_;
  s.joint_rad = {t.joint_angle_rad[kFrontJoint], t.joint_angle_rad[kRearJoint]};
  s.joint_error_rad = joint_error_rad(t);
  s.gait_state_changes = gait_state_changes_;
  s.axle_x_m = {0.5 * (t.wheel_position_m[kFrontLeft][0] + t.wheel_position_m[kFrontRight][0]),
                0.5 * (t.wheel_position_m[kBackLeft][0] + t.wheel_position_m[kBackRight][0])};
  return s;
}

void Metrics::observe_phases(const Session& session, double time_s, double forward_m,
                             std::optional<double> voltage_drop_v, double joint_error_rad,
                             double bound_excess_rad, const std::array<double, 2>& joint_rad,
                             double lateral_speed_mps,
                             std::optional<double> lateral_drift_mps) {
  for (PhaseWindow& w : phases_) {
    if (!w.start && time_s >= w.phase.from_s - kTimeEpsilonS) {
      w.start = snapshot(session, time_s);
      w.last_time_s = time_s;
    }
    if (!w.start || w.end) continue;
    // The forward position held over the cycle that ends now (the phase's last cycle included).
    w.forward_integral_m_s += forward_m * (time_s - w.last_time_s);
    w.forward_time_s += time_s - w.last_time_s;
    w.last_time_s = time_s;
    if (time_s >= w.phase.to_s - kTimeEpsilonS) {
      w.end = snapshot(session, time_s);
      continue;
    }
    w.max_joint_error_rad = std::max(w.max_joint_error_rad, joint_error_rad);
    w.max_bound_excess_rad = std::max(w.max_bound_excess_rad, bound_excess_rad);
    w.max_lateral_speed_mps = std::max(w.max_lateral_speed_mps, lateral_speed_mps);
    if (lateral_drift_mps) {
      w.max_lateral_drift_mps = std::max(w.max_lateral_drift_mps, *lateral_drift_mps);
    }
    for (std::size_t j = 0; j < 2; ++j) {
      w.min_joint_rad[j] = std::min(w.min_joint_rad[j], joint_rad[j]);
      w.max_joint_rad[j] = std::max(w.max_joint_rad[j], joint_rad[j]);
    }
    if (voltage_drop_v) w.max_voltage_drop_v = std::max(w.max_voltage_drop_v, *voltage_drop_v);
  }
}

void Metrics::observe(const Session& session, const CycleRecord& cycle) {
  const sim::GroundTruth t = session.rover().truth();
  const double now = static_cast<double>(cycle.time_us) * 1e-6;
  if (!started_) {
    started_ = true;
    start_position_m_ = last_position_m_ = t.position_m;
    start_yaw_rad_ = last_yaw_rad_ = t.roll_pitch_yaw_rad[2];
  }
  path_length_m_ += std::hypot(t.position_m[0] - last_position_m_[0],
                               t.position_m[1] - last_position_m_[1]);
  last_position_m_ = t.position_m;
  double dyaw = t.roll_pitch_yaw_rad[2] - last_yaw_rad_;
  dyaw = std::remainder(dyaw, 2.0 * std::numbers::pi);
  yaw_unwrapped_rad_ += dyaw;
  last_yaw_rad_ = t.roll_pitch_yaw_rad[2];
  min_supply_v_ = std::min(min_supply_v_, session.rover().electrics().supply_v);
  const auto& j = params_->joints;
  const double bound_excess_rad =
      std::max(bound_excess(t.joint_angle_rad[kFrontJoint], j.front_min_rad, j.front_max_rad),
               bound_excess(t.joint_angle_rad[kRearJoint], j.rear_min_rad, j.rear_max_rad));
  max_bound_excess_rad_ = std::max(max_bound_excess_rad_, bound_excess_rad);
  max_roll_rad_ = std::max(max_roll_rad_, std::abs(t.roll_pitch_yaw_rad[0]));
  max_pitch_rad_ = std::max(max_pitch_rad_, std::abs(t.roll_pitch_yaw_rad[1]));
  // Sideways: the horizontal velocity along the centre unit's left axis (its heading + 90°).
  const double yaw = t.roll_pitch_yaw_rad[2];
  const double lateral_speed_mps =
      std::abs(-std::sin(yaw) * t.velocity_mps[0] + std::cos(yaw) * t.velocity_mps[1]);
  max_lateral_speed_mps_ = std::max(max_lateral_speed_mps_, lateral_speed_mps);
  const std::optional<double> lateral_drift_mps =
      sideways_drift_.add(now, t.position_m[0], t.position_m[1], yaw);
  if (lateral_drift_mps) {
    max_lateral_drift_mps_ = std::max(max_lateral_drift_mps_, *lateral_drift_mps);
  }
  for (double slip : t.wheel_slip_mps) {
    slip_sum_ += std::abs(slip);
    max_slip_mps_ = std::max(max_slip_mps_, std::abs(slip));
    ++slip_samples_;
  }
  // Standing: no motor is driven and the body neither moves nor turns.
  bool driven = false;
  for (double d : session.rover().firmware().duty()) driven = driven || d != 0.0;
  if (driven) last_duty_s_ = now;
  if (driven || std::hypot(t.velocity_mps[0], t.velocity_mps[1]) > 0.01 ||
      std::abs(t.yaw_rate_radps) > kStandstillRadps) {
    last_motion_s_ = now;
  }
  std::optional<double> voltage_drop_v;
  const driver::DriverStatus& s = session.status();
  if (cycle.driver_running && s.mode == driver::DriverMode::kDriving && s.reference_supply_v > 0.0) {
    voltage_drop_v = s.reference_supply_v - s.supply_v;
  }
  observe_phases(session, now, t.position_m[0] - start_position_m_[0], voltage_drop_v,
                 joint_error_rad(t), bound_excess_rad,
                 {t.joint_angle_rad[kFrontJoint], t.joint_angle_rad[kRearJoint]},
                 lateral_speed_mps, lateral_drift_mps);
  follow_truth_odometry(session, cycle, truth_odometry_);
  if (!cycle.driver_running) return;
  observe_odometry(session);
  if (voltage_drop_v) {
    max_voltage_drop_v_ = std::max(max_voltage_drop_v_, *voltage_drop_v);
    min_max_duty_ = std::min(min_max_duty_, s.max_duty);
  }
  for (const auto& m : s.motors) max_abs_duty_ = std::max(max_abs_duty_, std::abs(m.duty));
  if (s.gait_state != last_gait_state_) ++gait_state_changes_;
  last_gait_state_ = s.gait_state;
  if (s.operator_timeout && !was_timed_out_) ++timeouts_;
  was_timed_out_ = s.operator_timeout;
  faults_ = std::max(faults_, static_cast<double>(s.faults.size()));
  const auto latched = [&s](std::string_view kind) {
    return std::any_of(s.faults.begin(), s.faults.end(),
                       [kind](const std::string& f) { return f.starts_with(kind); });
  };
  const bool tip_over = latched("tip-over");
  const bool stuck = latched("stuck");
  if (tip_over && !tip_over_latched_) {
    ++tip_over_faults_;
    if (first_tip_over_s_ < 0.0) first_tip_over_s_ = now;
  }
  if (stuck && !stuck_latched_) {
    ++stuck_faults_;
    if (first_stuck_s_ < 0.0) first_stuck_s_ = now;
  }
  tip_over_latched_ = tip_over;
  stuck_latched_ = stuck;
  const std::size_t joints_blocked = static_cast<std::size_t>(
      std::count_if(s.faults.begin(), s.faults.end(), [](const std::string& f) {
        return f.starts_with("front joint blocked") || f.starts_with("rear joint blocked");
      }));
  if (joints_blocked > joints_blocked_) {
    joint_blocked_faults_ += static_cast<double>(joints_blocked - joints_blocked_);
    if (first_joint_blocked_s_ < 0.0) first_joint_blocked_s_ = now;
  }
  joints_blocked_ = joints_blocked;
  max_joint_stall_s_ = std::max({max_joint_stall_s_, s.joint_stalled_s[0], s.joint_stalled_s[1]});
  other_faults_ = std::max(other_faults_, static_cast<double>(s.faults.size()) - (tip_over ? 1.0 : 0.0) -
                                              (stuck ? 1.0 : 0.0) -
                                              static_cast<double>(joints_blocked));
  malformed_ = static_cast<double>(s.bus.malformed);
  observe_missions(s.mission);
}

// Each mission counts once when it starts (a new id) and once when it ends (reached, aborted).
void Metrics::observe_missions(const navigation::MissionStatus& m) {
  if (m.id != last_mission_id_) {
    // A mission replaced by the next one never shows its end: it was aborted.
    if (last_mission_state_ == navigation::MissionState::kRunning &&
        m.kind != navigation::MissionKind::kNone) {
      ++missions_aborted_;
    }
    last_mission_id_ = m.id;
    last_mission_state_ = navigation::MissionState::kIdle;
    if (m.id != 0) ++missions_started_;  // 0: a restarted driver, no mission yet
  }
  if (m.state != last_mission_state_) {
    if (m.state == navigation::MissionState::kReached) {
      ++missions_reached_;
      mission_corrections_ += m.corrections;
    }
    if (m.state == navigation::MissionState::kAborted) ++missions_aborted_;
    last_mission_state_ = m.state;
  }
  final_mission_progress_ = m.progress;
}

void Metrics::add_phase_metrics(const PhaseWindow& w, const Snapshot& end,
                                std::map<std::string, double>& m) const {
  const Snapshot& start = *w.start;
  const std::string p = w.phase.name + ".";
  const double duration_s = end.time_s - start.time_s;
  const double dx = end.position_m[0] - start.position_m[0];
  const double dy = end.position_m[1] - start.position_m[1];
  const double path_m = end.path_length_m - start.path_length_m;
  const std::uint64_t samples = end.slip_samples - start.slip_samples;
  m[p + "duration_s"] = duration_s;
  m[p + "distance_m"] = std::hypot(dx, dy);
  m[p + "forward_distance_m"] = dx;
  m[p + "path_length_m"] = path_m;
  m[p + "mean_speed_mps"] = duration_s > 0.0 ? path_m / duration_s : 0.0;
  m[p + "yaw_change_rad"] = end.yaw_rad - start.yaw_rad;
  m[p + "yaw_rate_mean_radps"] = duration_s > 0.0 ? (end.yaw_rad - start.yaw_rad) / duration_s : 0.0;
  m[p + "climb_m"] = end.position_m[2] - start.position_m[2];
  m[p + "energy_used_j"] = end.energy_j - start.energy_j;
  m[p + "mean_abs_slip_mps"] = samples > 0 ? (end.slip_sum - start.slip_sum) / static_cast<double>(samples) : 0.0;
  m[p + "max_voltage_drop_v"] = w.max_voltage_drop_v;
  m[p + "final_front_joint_rad"] = end.joint_rad[0];
  m[p + "final_rear_joint_rad"] = end.joint_rad[1];
  m[p + "final_joint_error_rad"] = end.joint_error_rad;
  // The axle distances c of Figure 3.3 at the true joint angles (γf = −p6, γr = p7).
  m[p + "final_front_clearance_m"] = mobility::axle_clearance_m(
      mobility::front_joint_bending_rad(end.joint_rad[0]), params_->geometry);
  m[p + "final_rear_clearance_m"] = mobility::axle_clearance_m(
      mobility::rear_joint_bending_rad(end.joint_rad[1]), params_->geometry);
  m[p + "max_joint_error_rad"] = w.max_joint_error_rad;
  m[p + "max_joint_bound_excess_rad"] = w.max_bound_excess_rad;
  // A phase without a cycle inside it has no extremes: its end state's angles.
  const auto extreme = [&](double value, double fallback) { return std::abs(value) < 1e8 ? value : fallback; };
  m[p + "min_front_joint_rad"] = extreme(w.min_joint_rad[0], end.joint_rad[0]);
  m[p + "max_front_joint_rad"] = extreme(w.max_joint_rad[0], end.joint_rad[0]);
  m[p + "min_rear_joint_rad"] = extreme(w.min_joint_rad[1], end.joint_rad[1]);
  m[p + "max_rear_joint_rad"] = extreme(w.max_joint_rad[1], end.joint_rad[1]);
  m[p + "gait_state_changes"] = end.gait_state_changes - start.gait_state_changes;
  m[p + "max_lateral_speed_mps"] = w.max_lateral_speed_mps;
  m[p + "max_lateral_drift_mps"] = w.max_lateral_drift_mps;
  // How far each exterior axle went along x (Field Experiment 6.2: with a rigid wheel "the
  // exterior axle was immobile" during wheel walking).
  m[p + "front_axle_forward_m"] = end.axle_x_m[0] - start.axle_x_m[0];
  m[p + "rear_axle_forward_m"] = end.axle_x_m[1] - start.axle_x_m[1];
  // The forward position (x from the run's start) averaged over the phase's time: the difference
  // of two phases' means is an advance that a gait's strokes, back and forth, do not blur.
  m[p + "mean_forward_m"] = w.forward_time_s > 0.0 ? w.forward_integral_m_s / w.forward_time_s
                                                   : end.position_m[0] - start_position_m_[0];
}

void Metrics::observe_odometry(const Session& session) {
  const driver::DriverStatus& s = session.status();
  // The driver's odometry frame starts where its start-up ends (driver.cpp, update_pose).
  if (s.cycle == 1 || !odometry_started_ || s.startup_phase != driver::StartupPhase::kDone) {
    odometry_started_ = true;
    odometry_origin_path_m_ = path_length_m_;
    wheel_pose_ = {};
  }
  // diff_drive_controller's formula, each side the mean of its three wheels.
  const auto& m = s.motors;
  const double left = (m[kFrontLeft].velocity_radps + m[kCenterLeft].velocity_radps +
                       m[kBackLeft].velocity_radps) / 3.0;
  const double right = (m[kFrontRight].velocity_radps + m[kCenterRight].velocity_radps +
                        m[kBackRight].velocity_radps) / 3.0;
  const double h = params_->cycle.period_s;
  const double r = params_->geometry.wheel_radius_m;
  const double ds = r * 0.5 * (left + right) * h;
  const double dpsi = r * (right - left) / params_->geometry.track_width_m * h;
  const double mid = wheel_pose_[2] + 0.5 * dpsi;
  wheel_pose_[0] += ds * std::cos(mid);
  wheel_pose_[1] += ds * std::sin(mid);
  wheel_pose_[2] += dpsi;
}

void Metrics::add_odometry_metrics(const Session& session, std::map<std::string, double>& m) const {
  if (!odometry_started_) return;
  // The truth's displacement since the origin, in the frame of the heading there.
  const estimation::PlanarPose truth = truth_odometry_.pose();
  const double x = truth.x_m;
  const double y = truth.y_m;
  const double heading = truth.heading_rad;
  const estimation::Pose& p = session.status().pose;
  const double error = std::hypot(p.x_m - x, p.y_m - y);
  const double path = path_length_m_ - odometry_origin_path_m_;
  m["odometry_position_error_m"] = error;
  m["odometry_position_error_share"] = path > 0.0 ? error / path : 0.0;
  m["odometry_heading_error_rad"] = std::abs(p.heading_rad - heading);
  m["odometry_position_sigma_m"] = p.position_sigma_m();
  m["wheel_odometry_position_error_m"] = std::hypot(wheel_pose_[0] - x, wheel_pose_[1] - y);
  m["wheel_odometry_heading_error_rad"] = std::abs(wheel_pose_[2] - heading);
}

std::map<std::string, double> Metrics::finish(const Session& session) const {
  const sim::GroundTruth t = session.rover().truth();
  std::map<std::string, double> m;
  m["distance_m"] = std::hypot(last_position_m_[0] - start_position_m_[0],
                               last_position_m_[1] - start_position_m_[1]);
  m["forward_distance_m"] = last_position_m_[0] - start_position_m_[0];
  m["path_length_m"] = path_length_m_;
  m["yaw_change_rad"] = yaw_unwrapped_rad_;
  m["climb_m"] = last_position_m_[2] - start_position_m_[2];
  m["mean_speed_mps"] = session.time_s() > 0.0 ? path_length_m_ / session.time_s() : 0.0;
  m["max_voltage_drop_v"] = max_voltage_drop_v_;
  m["min_supply_v"] = min_supply_v_;
  m["max_abs_duty"] = max_abs_duty_;
  m["min_max_duty"] = min_max_duty_;
  m["max_joint_bound_excess_rad"] = max_bound_excess_rad_;
  m["final_front_joint_rad"] = t.joint_angle_rad[kFrontJoint];
  m["final_rear_joint_rad"] = t.joint_angle_rad[kRearJoint];
  m["final_front_joint_max_rad"] = session.status().joint_bounds.front_max_rad;
  m["final_rear_joint_min_rad"] = session.status().joint_bounds.rear_min_rad;
  m["final_joint_error_rad"] = joint_error_rad(t);
  m["mean_abs_slip_mps"] = slip_samples_ > 0 ? slip_sum_ / static_cast<double>(slip_samples_) : 0.0;
  m["max_slip_mps"] = max_slip_mps_;
  m["gait_state_changes"] = gait_state_changes_;
  m["operator_timeouts"] = timeouts_;
  m["driver_faults"] = faults_;
  m["max_roll_rad"] = max_roll_rad_;
  m["max_pitch_rad"] = max_pitch_rad_;
  m["tip_over_faults"] = tip_over_faults_;
  m["stuck_faults"] = stuck_faults_;
  m["joint_blocked_faults"] = joint_blocked_faults_;
  m["first_tip_over_s"] = first_tip_over_s_;
  m["first_stuck_s"] = first_stuck_s_;
  m["first_joint_blocked_s"] = first_joint_blocked_s_;
  m["max_joint_stall_s"] = max_joint_stall_s_;
  m["other_faults"] = other_faults_;
  m["missions_started"] = missions_started_;
  m["missions_reached"] = missions_reached_;
  m["missions_aborted"] = missions_aborted_;
  m["mission_corrections"] = mission_corrections_;
  m["final_mission_progress"] = final_mission_progress_;
  m["max_lateral_speed_mps"] = max_lateral_speed_mps_;
  m["max_lateral_drift_mps"] = max_lateral_drift_mps_;
  m["malformed_frames"] = malformed_;
  m["brownouts"] = static_cast<double>(session.rover().electrics().brownout_count);
  m["max_supply_current_a"] = session.rover().electrics().peak_total_current_a;
  m["driver_restarts"] = static_cast<double>(session.driver_restarts());
  m["energy_used_j"] = session.rover().energy_used_j();
  double final_duty = 0.0;
  for (double d : session.rover().firmware().duty()) final_duty = std::max(final_duty, std::abs(d));
  m["final_max_abs_duty"] = final_duty;
  if (stop_mark_s_) {
    m["time_to_motors_off_s"] = std::max(0.0, last_duty_s_ - *stop_mark_s_);
    m["time_to_standstill_s"] = std::max(0.0, last_motion_s_ - *stop_mark_s_);
  }
  add_odometry_metrics(session, m);
  add_soil_metrics(session, m["distance_m"], m);
  for (const PhaseWindow& w : phases_) {
    if (!w.start) continue;  // the run ended before the phase began
    add_phase_metrics(w, w.end ? *w.end : snapshot(session, session.time_s()), m);
  }
  return m;
}

}  // namespace marsokhod::runner
