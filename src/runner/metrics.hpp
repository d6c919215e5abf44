// The named numbers a scenario reports and checks, units in their names. Collected every cycle
// from the driver's status and the simulator's ground truth.
#pragma once

#include <map>
#include <optional>
#include <string>

#include "core/params.hpp"
#include "runner/session.hpp"

namespace marsokhod::runner {

class Metrics {
 public:
  explicit Metrics(const Params& params) : params_(&params) {}

  // After every cycle. `stop_mark`: the operator went silent or the driver halted at this time
  // (for time_to_standstill_s). `joint_targets`: the position targets of the input in force.
  void observe(const Session& session, const CycleRecord& cycle);
  void mark_stop(double time_s);
  void set_joint_targets(std::optional<double> front_rad, std::optional<double> rear_rad);

  std::map<std::string, double> finish(const Session& session) const;

 private:
  const Params* params_;
  bool started_ = false;
  std::array<double, 3> start_position_m_{};
  std::array<double, 3> last_position_m_{};
  double path_length_m_ = 0.0;
  double start_yaw_rad_ = 0.0, last_yaw_rad_ = 0.0, yaw_unwrapped_rad_ = 0.0;
  double max_voltage_drop_v_ = 0.0;
  double min_supply_v_ = 1e9;
  double max_abs_duty_ = 0.0;
  double min_max_duty_ = 1.0;
  double max_bound_excess_rad_ = 0.0;
  double slip_sum_ = 0.0, max_slip_mps_ = 0.0;
  std::uint64_t slip_samples_ = 0;
  double gait_state_changes_ = 0.0;
  std::size_t last_gait_state_ = 0;
  double timeouts_ = 0.0;
  bool was_timed_out_ = true;
  double faults_ = 0.0;
  double malformed_ = 0.0;
  std::optional<double> stop_mark_s_;
  double last_motion_s_ = 0.0;
  std::optional<double> front_target_rad_, rear_target_rad_;
};

}  // namespace marsokhod::runner
