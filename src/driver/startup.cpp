#include "driver/startup.hpp"

#include <algorithm>
#include <cmath>

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

Startup::Startup(const Params& params) : params_(&params) {}

void Startup::advance() {
  if (phase_ == StartupPhase::kConfigure &&
      std::all_of(configured_.begin(), configured_.end(), [](bool c) { return c; })) {
    phase_ = params_->safety.dead_man_dog > 0 ? StartupPhase::kEnableDeadMan
                                              : StartupPhase::kCalibrate;
  }
}

void Startup::take_joints(std::array<double, 2> max_travel_rad) {
  joints_taken_ = true;
  for (std::size_t j = 0; j < 2; ++j) max_travel_rad_[j] = std::max(0.0, max_travel_rad[j]);
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
    const double widest_gap = std::min((on_slope ? 1.0 - u : 1.0 + u) * gap[j], max_travel_rad_[j]);
    const bool settled = time_s - calibration_start_s_ >= kEngagementSettle_s;
    const bool slowed = std::abs(shaft_speed_radps[j]) <
                        kEngagedSpeedShare * std::abs(no_load_speed_radps[j]);
    if ((settled && slowed) || shaft_start_rad_[j] - shaft_rad[j] >= widest_gap) {
      gap_closed_[j] = true;
    }
    duty[j] = gap_closed_[j] ? 0.0 : -params_->operator_input.calibration_duty;
    stopped = stopped && gap_closed_[j] && std::abs(shaft_speed_radps[j]) < kShaftStoppedRadps;
  }
  const bool timed_out = time_s - calibration_start_s_ >= kCalibrationTimeout_s;
  if (stopped || timed_out) {
    phase_ = StartupPhase::kDone;
    return {0.0, 0.0};
  }
  return duty;
}

}  // namespace marsokhod::driver
