#include "core/adaptation/backlash.hpp"

#include <algorithm>
#include <utility>

#include "core/checks/checks.hpp"

namespace marsokhod::adaptation {
namespace {

void check_arguments(const char* function, double motor_position_rad, double joint_position_rad,
                     double backlash_rad) {
  checks::require_finite(motor_position_rad, function, "motor_position_rad");
  checks::require_finite(joint_position_rad, function, "joint_position_rad");
  checks::require_non_negative(backlash_rad, function, "backlash_rad");
}

// P⁺ without the checks; the callers have made them.
double factor_positive(double motor_position_rad, double joint_position_rad, double backlash_rad) {
  if (backlash_rad == 0.0) {
    return 1.0;
  }
  return std::clamp((motor_position_rad - joint_position_rad) / backlash_rad, 0.0, 1.0);
}

double position(double motor_position_rad, double joint_position_rad, double backlash_rad) {
  if (motor_position_rad < joint_position_rad) {
    return motor_position_rad;
  }
  if (motor_position_rad > joint_position_rad + backlash_rad) {
    return motor_position_rad - backlash_rad;
  }
  return joint_position_rad;
}

double velocity(double motor_position_rad, double motor_velocity_radps, double joint_position_rad,
                double backlash_rad) {
  if (motor_velocity_radps == 0.0) {
    return 0.0;
  }
  if (backlash_rad == 0.0) {
    return motor_velocity_radps;
  }
  const double positive = factor_positive(motor_position_rad, joint_position_rad, backlash_rad);
  return motor_velocity_radps * (motor_velocity_radps > 0.0 ? positive : 1.0 - positive);
}

}  // namespace

double backlash_position(double motor_position_rad, double joint_position_rad,
                         double backlash_rad) {
  check_arguments("backlash_position", motor_position_rad, joint_position_rad, backlash_rad);
  return position(motor_position_rad, joint_position_rad, backlash_rad);
}

double backlash_factor_positive(double motor_position_rad, double joint_position_rad,
                                double backlash_rad) {
  check_arguments("backlash_factor_positive", motor_position_rad, joint_position_rad, backlash_rad);
  return factor_positive(motor_position_rad, joint_position_rad, backlash_rad);
}

double backlash_factor_negative(double motor_position_rad, double joint_position_rad,
                                double backlash_rad) {
  check_arguments("backlash_factor_negative", motor_position_rad, joint_position_rad, backlash_rad);
  if (backlash_rad == 0.0) {
    return 1.0;
  }
  return 1.0 - factor_positive(motor_position_rad, joint_position_rad, backlash_rad);
}

double backlash_velocity(double motor_position_rad, double motor_velocity_radps,
                         double joint_position_rad, double backlash_rad) {
  check_arguments("backlash_velocity", motor_position_rad, joint_position_rad, backlash_rad);
  checks::require_finite(motor_velocity_radps, "backlash_velocity", "motor_velocity_radps");
  return velocity(motor_position_rad, motor_velocity_radps, joint_position_rad, backlash_rad);
}

BacklashTracker::BacklashTracker(double backlash_rad, double initial_position_rad)
    : backlash_rad_(backlash_rad), joint_position_rad_(initial_position_rad) {
  checks::require_non_negative(backlash_rad, "BacklashTracker", "backlash_rad");
  checks::require_finite(initial_position_rad, "BacklashTracker", "initial_position_rad");
}

void BacklashTracker::update(double motor_position_rad, double motor_velocity_radps) {
  checks::require_finite(motor_position_rad, "BacklashTracker::update", "motor_position_rad");
  checks::require_finite(motor_velocity_radps, "BacklashTracker::update", "motor_velocity_radps");
  // (4.2) reads p^k, so the velocity goes first.
  joint_velocity_radps_ =
      velocity(motor_position_rad, motor_velocity_radps, joint_position_rad_, backlash_rad_);
  joint_position_rad_ = position(motor_position_rad, joint_position_rad_, backlash_rad_);
}

void BacklashTracker::reset(double position_rad) {
  checks::require_finite(position_rad, "BacklashTracker::reset", "position_rad");
  joint_position_rad_ = position_rad;
  joint_velocity_radps_ = 0.0;
}

namespace {

// BacklashTracker has no default state, so the array is built in place.
template <std::size_t... I>
std::array<BacklashTracker, kMotorCount> make_trackers(const MotorVector& backlash_rad,
                                                       const MotorVector& initial_position_rad,
                                                       std::index_sequence<I...> /*motors*/) {
  return {BacklashTracker(backlash_rad[I], initial_position_rad[I])...};
}

std::array<BacklashTracker, kMotorCount> make_trackers(const MotorVector& backlash_rad,
                                                       const MotorVector& initial_position_rad) {
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    checks::require_non_negative(backlash_rad[i], "RoverBacklashTracker",
                                 checks::Element{"backlash_rad", i});
    checks::require_finite(initial_position_rad[i], "RoverBacklashTracker",
                           checks::Element{"initial_position_rad", i});
  }
  return make_trackers(backlash_rad, initial_position_rad, std::make_index_sequence<kMotorCount>{});
}

void check_all_finite(const MotorVector& values, const char* function, const char* argument) {
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    checks::require_finite(values[i], function, checks::Element{argument, i});
  }
}

}  // namespace

RoverBacklashTracker::RoverBacklashTracker(const MotorParams& motors)
    : RoverBacklashTracker(motors.backlash_rad, motors.initial_position_rad) {}

RoverBacklashTracker::RoverBacklashTracker(const MotorVector& backlash_rad,
                                           const MotorVector& initial_position_rad)
    : trackers_(make_trackers(backlash_rad, initial_position_rad)) {}

void RoverBacklashTracker::update(const MotorVector& motor_position_rad,
                                  const MotorVector& motor_velocity_radps) {
  check_all_finite(motor_position_rad, "RoverBacklashTracker::update", "motor_position_rad");
  check_all_finite(motor_velocity_radps, "RoverBacklashTracker::update", "motor_velocity_radps");
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    trackers_[i].update(motor_position_rad[i], motor_velocity_radps[i]);
  }
}

void RoverBacklashTracker::reset(const MotorVector& initial_position_rad) {
  check_all_finite(initial_position_rad, "RoverBacklashTracker::reset", "initial_position_rad");
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    trackers_[i].reset(initial_position_rad[i]);
  }
}

MotorVector RoverBacklashTracker::joint_position_rad() const {
  MotorVector result{};
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    result[i] = trackers_[i].joint_position_rad();
  }
  return result;
}

MotorVector RoverBacklashTracker::joint_velocity_radps() const {
  MotorVector result{};
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    result[i] = trackers_[i].joint_velocity_radps();
  }
  return result;
}

}  // namespace marsokhod::adaptation
