#include "driver/startup.hpp"

#include <algorithm>
#include <cmath>

#include "core/adaptation/motor_curve.hpp"
#include "core/adaptation/no_load_velocity.hpp"
#include "driver/joint_margin.hpp"

namespace marsokhod::driver {

std::string_view phase_name(StartupPhase phase) {
  switch (phase) {
    case StartupPhase::kConfigure: return "configure";
    case StartupPhase::kEnableDeadMan: return "dead-man";
    case StartupPhase::kCalibrate: return "calibrate";
    case StartupPhase::kDone: return "done";
  }
  return "?";
}

Startup::Startup(const Params& params)
    : params_(&params), run_on_s_(joint_dead_time_s(params) + params.cycle.period_s) {
  const adaptation::MotorCurve curve(
      adaptation::select_motor_curve(params.motor_curves, params.cycle.icr));
  const std::array<std::size_t, 2> joints{kFrontJoint, kRearJoint};
  for (std::size_t k = 0; k < 2; ++k) {
    const double free_speed = adaptation::no_load_velocity(
        curve, params.operator_input.calibration_duty, params.motors.scale[joints[k]],
        params.motors.nominal_supply_v, params.motors.nominal_supply_v);
    free_run_on_rad_[k] = std::abs(free_speed) * run_on_s_;
  }
}

void Startup::advance() {
  if (phase_ == StartupPhase::kConfigure &&
      std::all_of(configured_.begin(), configured_.end(), [](bool c) { return c; })) {
    phase_ = params_->safety.dead_man_dog > 0 ? StartupPhase::kEnableDeadMan
                                              : StartupPhase::kCalibrate;
  }
}

void Startup::take_joints(std::array<double, 2> max_travel_rad) {
  joints_taken_ = true;
  for (std::size_t j = 0; j < 2; ++j) {
    // Less than the calibration duty's free run-on: not started at all (see the header).
    take_up_allowed_rad_[j] = max_travel_rad[j];
    take_up_skipped_[j] = !(max_travel_rad[j] >= free_run_on_rad_[j]);  // NaN too
    max_travel_rad_[j] = take_up_skipped_[j] ? 0.0 : max_travel_rad[j];
  }
}

void Startup::on_configured(std::size_t motor) {
  configured_.at(motor) = true;
  advance();
}

void Startup::on_dead_man_acknowledged() {
  if (phase_ == StartupPhase::kEnableDeadMan) phase_ = StartupPhase::kCalibrate;
  advance();
}

std::array<double, 2> Startup::calibrate(double time_s, const std::array<double, 2>& shaft_rad,
                                         const std::array<double, 2>& shaft_speed_radps,
                                         const std::array<double, 2>& no_load_speed_radps,
                                         bool on_slope) {
  if (phase_ != StartupPhase::kCalibrate || (continue_joints_ && !joints_taken_)) return {0.0, 0.0};
  if (!calibration_started_) {
    calibration_started_ = true;
    calibration_start_s_ = time_s;
    shaft_start_rad_ = shaft_rad;
  }
  const std::array<double, 2> gap{params_->motors.backlash_rad[kFrontJoint],
                                  params_->motors.backlash_rad[kRearJoint]};
  std::array<double, 2> duty{};
  bool stopped = true;
  for (std::size_t j = 0; j < 2; ++j) {
    // The shaft moves toward the negative end of the gap; once it meets the joint it rests.
    const double u = params_->joints.backlash_uncertainty;
    const double gap_limit = (on_slope ? 1.0 - u : 1.0 + u) * gap[j];
    const double widest_gap = std::min(gap_limit, max_travel_rad_[j]);
    const bool settled = time_s - calibration_start_s_ >= kEngagementSettle_s;
    const double speed = std::abs(shaft_speed_radps[j]);
    // A limit that keeps the joint inside (5.3) (the slope's narrowest gap, a restart's
    // p̄ − p_min) is anticipated by how far the shaft runs on after the decision, perhaps
    // dragging its joint: its speed over the dead time and the duty rule's last step
    // (run_on_s_). The speed is |w̄|, but at least the calibration duty's free speed: a shaft
    // that has just started reads slower than the duties already sent will turn it.
    const bool keeps_bound = on_slope || max_travel_rad_[j] < gap_limit;
    const double run_on =
        keeps_bound ? std::max(speed * run_on_s_, free_run_on_rad_[j]) : 0.0;
    const bool slowed = speed < kEngagedSpeedShare * std::abs(no_load_speed_radps[j]);
    // Against the crossing's own free speed: the shaft meets its joint within a cycle or two of
    // slowing (ν/2 alone lets a joint that gives way easily, a wheel on soft soil, go on for
    // 0.1 s: 0.01 rad on the soft sand).
    bool dropped = false;
    bool slowing = false;  // below the free speed: the shaft is meeting its joint
    if (settled && !gap_closed_[j]) {
      const double free = free_samples_[j] > 0 ? free_speed_sum_[j] / free_samples_[j] : 0.0;
      if (free_samples_[j] >= kMinFreeSamples && speed < kMetSpeedShare * free) {
        dropped = true;
      } else if (speed >= kFreeSpeedShare * free) {
        free_speed_sum_[j] += speed;
        ++free_samples_[j];
        free_shaft_rad_[j] = shaft_rad[j];
      }
      slowing = free_samples_[j] > 0 && speed < kFreeSpeedShare * free;
    }
    if (!gap_closed_[j] && settled && (slowed || dropped)) {
      gap_closed_[j] = true;
      met_[j] = free_samples_[j] > 0;
    } else if (!gap_closed_[j] && shaft_start_rad_[j] - shaft_rad[j] + run_on >= widest_gap) {
      gap_closed_[j] = true;  // at the travel limit, perhaps just as it met its joint
      met_[j] = slowing;
    }
    duty[j] = gap_closed_[j] ? 0.0 : -params_->operator_input.calibration_duty;
    stopped = stopped && gap_closed_[j] && std::abs(shaft_speed_radps[j]) < kShaftStoppedRadps;
  }
  last_shaft_rad_ = shaft_rad;
  const bool timed_out = time_s - calibration_start_s_ >= kCalibrationTimeout_s;
  if (stopped || timed_out) {
    phase_ = StartupPhase::kDone;
    return {0.0, 0.0};
  }
  return duty;
}

std::array<double, 2> Startup::over_travel_rad() const {
  std::array<double, 2> travel{};
  for (std::size_t j = 0; j < 2; ++j) {
    if (met_[j]) travel[j] = std::max(0.0, free_shaft_rad_[j] - last_shaft_rad_[j]);
  }
  return travel;
}

}  // namespace marsokhod::driver
