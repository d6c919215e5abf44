#include "core/mobility/elementary_motion.hpp"

#include <cstddef>

#include "core/checks/checks.hpp"

namespace marsokhod::mobility {
namespace {

MotorVector single_motor(MotorIndex index) {
  MotorVector motion{};
  motion[index] = 1.0;
  return motion;
}

}  // namespace

MotorVector drive_straight_motion() {
  MotorVector motion{};
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    motion[i] = 1.0;
  }
  return motion;
}

MotorVector sideways_drift_motion() {
  MotorVector motion{};
  motion[kBackLeft] = 1.0;
  motion[kFrontLeft] = -1.0;
  motion[kBackRight] = -1.0;
  motion[kFrontRight] = 1.0;
  return motion;
}

MotorVector trench_motion() { return single_motor(kFrontRight); }
MotorVector front_joint_motion() { return single_motor(kFrontJoint); }
MotorVector rear_joint_motion() { return single_motor(kRearJoint); }

double spin_ratio(double clearance_m, const SpinParams& spin) {
  checks::law::require_finite(clearance_m, "spin_ratio", "clearance_m (c)");
  checks::law::require_finite(spin.slope_per_m, "spin_ratio", "SpinParams::slope_per_m");
  checks::law::require_finite(spin.offset, "spin_ratio", "SpinParams::offset");
  return spin.slope_per_m * clearance_m + spin.offset;
}

MotorVector spin_motion(double front_clearance_m, double rear_clearance_m, const SpinParams& spin) {
  const double front = spin_ratio(front_clearance_m, spin);
  const double rear = spin_ratio(rear_clearance_m, spin);
  MotorVector motion{};
  motion[kBackLeft] = -rear;
  motion[kCenterLeft] = -1.0;
  motion[kFrontLeft] = -front;
  motion[kBackRight] = rear;
  motion[kCenterRight] = 1.0;
  motion[kFrontRight] = front;
  return motion;
}

MotorVector driving_motion(const DrivingSpeeds& speeds, double front_clearance_m,
                           double rear_clearance_m, const SpinParams& spin) {
  checks::law::require_finite(speeds.drive_radps, "driving_motion", "drive_radps (v1)");
  checks::law::require_finite(speeds.spin_radps, "driving_motion", "spin_radps (v2)");
  checks::law::require_finite(speeds.drift_radps, "driving_motion", "drift_radps (v3)");
  checks::law::require_finite(speeds.trench_radps, "driving_motion", "trench_radps (v4)");
  MotorVector motion{};
  add_scaled(motion, drive_straight_motion(), speeds.drive_radps);
  add_scaled(motion, spin_motion(front_clearance_m, rear_clearance_m, spin), speeds.spin_radps);
  add_scaled(motion, sideways_drift_motion(), speeds.drift_radps);
  add_scaled(motion, trench_motion(), speeds.trench_radps);
  return motion;
}

void add_scaled(MotorVector& into, const MotorVector& motion, double coefficient) {
  checks::law::require_finite(coefficient, "add_scaled", "coefficient (v_j)");
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    into[i] += motion[i] * coefficient;
  }
}

}  // namespace marsokhod::mobility
