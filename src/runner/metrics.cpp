#include "runner/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace marsokhod::runner {
namespace {

constexpr double kStandstillRadps = 0.05;  // every shaft slower than this: standing

double bound_excess(double p, double min, double max) {
  return std::max({0.0, min - p, p - max});
}

}  // namespace

void Metrics::mark_stop(double time_s) {
  if (!stop_mark_s_) stop_mark_s_ = time_s;
}

void Metrics::set_joint_targets(std::optional<double> front_rad, std::optional<double> rear_rad) {
  front_target_rad_ = front_rad;
  rear_target_rad_ = rear_rad;
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
  max_bound_excess_rad_ = std::max({max_bound_excess_rad_,
                                    bound_excess(t.joint_angle_rad[kFrontJoint], j.front_min_rad, j.front_max_rad),
                                    bound_excess(t.joint_angle_rad[kRearJoint], j.rear_min_rad, j.rear_max_rad)});
  for (double slip : t.wheel_slip_mps) {
    slip_sum_ += std::abs(slip);
    max_slip_mps_ = std::max(max_slip_mps_, std::abs(slip));
    ++slip_samples_;
  }
  // Standing: no motor is driven and the body neither moves nor turns.
  bool moving = std::hypot(t.velocity_mps[0], t.velocity_mps[1]) > 0.01 ||
                std::abs(t.yaw_rate_radps) > kStandstillRadps;
  for (double d : session.rover().firmware().duty()) moving = moving || d != 0.0;
  if (moving) last_motion_s_ = now;
  if (!cycle.driver_running) return;
  const driver::DriverStatus& s = session.status();
  if (s.mode == driver::DriverMode::kDriving && s.reference_supply_v > 0.0) {
    max_voltage_drop_v_ = std::max(max_voltage_drop_v_, s.reference_supply_v - s.supply_v);
    min_max_duty_ = std::min(min_max_duty_, s.max_duty);
  }
  for (const auto& m : s.motors) max_abs_duty_ = std::max(max_abs_duty_, std::abs(m.duty));
  if (s.gait_state != last_gait_state_) ++gait_state_changes_;
  last_gait_state_ = s.gait_state;
  if (s.operator_timeout && !was_timed_out_) ++timeouts_;
  was_timed_out_ = s.operator_timeout;
  faults_ = std::max(faults_, static_cast<double>(s.faults.size()));
  malformed_ = static_cast<double>(s.bus.malformed);
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
  double error = 0.0;
  if (front_target_rad_) error = std::max(error, std::abs(t.joint_angle_rad[kFrontJoint] - *front_target_rad_));
  if (rear_target_rad_) error = std::max(error, std::abs(t.joint_angle_rad[kRearJoint] - *rear_target_rad_));
  m["final_joint_error_rad"] = error;
  m["mean_abs_slip_mps"] = slip_samples_ > 0 ? slip_sum_ / static_cast<double>(slip_samples_) : 0.0;
  m["max_slip_mps"] = max_slip_mps_;
  m["gait_state_changes"] = gait_state_changes_;
  m["operator_timeouts"] = timeouts_;
  m["driver_faults"] = faults_;
  m["malformed_frames"] = malformed_;
  m["brownouts"] = static_cast<double>(session.rover().electrics().brownout_count);
  m["driver_restarts"] = static_cast<double>(session.driver_restarts());
  m["energy_used_j"] = session.rover().energy_used_j();
  double final_duty = 0.0;
  for (double d : session.rover().firmware().duty()) final_duty = std::max(final_duty, std::abs(d));
  m["final_max_abs_duty"] = final_duty;
  if (stop_mark_s_) {
    m["time_to_standstill_s"] = std::max(0.0, last_motion_s_ - *stop_mark_s_);
  }
  return m;
}

}  // namespace marsokhod::runner
