// The named numbers a scenario reports and checks, units in their names. Collected every cycle
// from the driver's status and the simulator's ground truth.
//
// For the whole run (run_metric_names()): distance_m, forward_distance_m (along the start
// heading, +x), path_length_m, yaw_change_rad, climb_m, mean_speed_mps, max_voltage_drop_v
// (Ū − U while driving), min_supply_v, max_abs_duty, min_max_duty (D), max_joint_bound_excess_rad
// (beyond (5.3), ground truth), final_front_joint_rad, final_rear_joint_rad,
// final_front_joint_max_rad and final_rear_joint_min_rad (the driver's bounds p6_max, p7_min at
// the end, after the slant response (6.4)), final_joint_error_rad (to the joint targets of the last input), mean_abs_slip_mps,
// max_slip_mps, gait_state_changes, operator_timeouts, driver_faults, malformed_frames,
// brownouts, max_supply_current_a (the supply's largest current over every physics step, ground
// truth), driver_restarts, energy_used_j, final_max_abs_duty (what µ0–µ7 apply at the end),
// and, only when the operator fell silent or the driver halted: time_to_motors_off_s (from then
// to the last cycle a duty cycle was applied by µ0–µ7) and time_to_standstill_s (to the last
// cycle with a duty applied, the body moving faster than 0.01 m/s or turning faster than
// 0.05 rad/s). The dead reckoning against the truth, from the end of the driver's last start-up to
// the end, the truth carried into the driver's odometry frame: odometry_position_error_m,
// odometry_position_error_share (of the path length since then), odometry_heading_error_rad,
// odometry_position_sigma_m (the estimate's own 1-σ), and the same errors of the plain wheel
// odometry of diff_drive_controller's formula over the three wheels of each side (v = r·(w̄_L +
// w̄_R)/2, ω = r·(w̄_R − w̄_L)/track): wheel_odometry_position_error_m,
// wheel_odometry_heading_error_rad. The failsafes: max_roll_rad and max_pitch_rad (|roll|,
// |pitch| of the centre unit, ground truth, the whole run), tip_over_faults, stuck_faults and
// joint_blocked_faults (how often the driver latched that fault; a joint blocked: either joint's),
// first_tip_over_s, first_stuck_s and first_joint_blocked_s (when it first did; −1: never),
// max_joint_stall_s (the longest either joint stood stalled under its command, the driver's
// joint_stalled_s: how near the joint-blocked failsafe came), other_faults (like driver_faults,
// the most faults latched at once, not counting these three). The operator's missions
// (core/navigation/mission.hpp): missions_started, missions_reached, missions_aborted (each
// mission once; a driver restart starts counting its missions again from its own ids),
// mission_corrections (legs driven again, over the reached missions), final_mission_progress (the
// last mission's progress at the end, 0..1).
// max_lateral_speed_mps: the largest sideways speed of the centre unit (ground truth, its
// horizontal velocity along its left axis; Field Experiment 5.2); max_lateral_drift_mps: the
// largest sideways travel over any second, per second, each step along the heading it had
// (sideways_drift.hpp: what carries the rover sideways, not how it shakes). On soft soil the
// soil's volumes, compaction and rut depths of soil_metrics.hpp.
//
// For each [[phase]] (phase_metric_names()), named "PHASE.metric": duration_s, distance_m,
// forward_distance_m, path_length_m, mean_speed_mps (path length / duration), yaw_change_rad,
// yaw_rate_mean_radps (yaw change / duration, signed: + counter-clockwise), climb_m,
// energy_used_j, mean_abs_slip_mps, max_voltage_drop_v, final_front_joint_rad,
// final_rear_joint_rad and final_joint_error_rad (at the phase's end, to the targets in force
// then), max_joint_error_rad (the largest joint error to the targets in force during the phase,
// 0 without targets: Procedure 4.17's "within 0.05 rad during 1 s" over a 1-s phase),
// final_front_clearance_m and final_rear_clearance_m (the axle distances c_f, c_r of Figure 3.3
// at the phase's end, from the true joint angles), max_joint_bound_excess_rad (beyond (5.3), ground truth, during the phase), min_front_joint_rad,
// max_front_joint_rad, min_rear_joint_rad and max_rear_joint_rad (the joint angles' extremes
// during the phase, ground truth: what the slant response (6.4) bounds), gait_state_changes,
// max_lateral_speed_mps, max_lateral_drift_mps (windows ending within the phase),
// front_axle_forward_m and rear_axle_forward_m (how far the midpoint of
// each exterior axle's wheels went along x, ground truth), mean_forward_m (the rover's x from
// the run's start, ground truth, averaged over the phase's time). A phase starts at
// the first cycle at or after from_s and ends at the first at or after to_s (or with the run).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/estimation/odometry_frame.hpp"
#include "core/params.hpp"
#include "runner/scenario.hpp"
#include "runner/session.hpp"
#include "runner/sideways_drift.hpp"

namespace marsokhod::runner {

const std::vector<std::string>& run_metric_names();
const std::vector<std::string>& phase_metric_names();
// A run metric, or "PHASE.metric" with a phase of that name and a phase metric.
bool is_metric_name(const std::string& name, const std::vector<Phase>& phases);

class Metrics {
 public:
  explicit Metrics(const Params& params, const std::vector<Phase>& phases = {});

  // After every cycle. `stop_mark`: the operator went silent or the driver halted at this time
  // (for time_to_standstill_s). `joint_targets`: the position targets of the input in force.
  void observe(const Session& session, const CycleRecord& cycle);
  void mark_stop(double time_s);
  void set_joint_targets(std::optional<double> front_rad, std::optional<double> rear_rad);

  std::map<std::string, double> finish(const Session& session) const;

 private:
  // What the run's accumulators and the truth read at one cycle.
  struct Snapshot {
    double time_s = 0.0;
    std::array<double, 3> position_m{};
    double yaw_rad = 0.0;  // unwrapped
    double path_length_m = 0.0;
    double energy_j = 0.0;
    double slip_sum = 0.0;
    std::uint64_t slip_samples = 0;
    std::array<double, 2> joint_rad{};
    double joint_error_rad = 0.0;
    double gait_state_changes = 0.0;
    std::array<double, 2> axle_x_m{};  // the front and rear axles' midpoints along x (truth)
  };
  struct PhaseWindow {
    Phase phase;
    std::optional<Snapshot> start, end;
    double max_voltage_drop_v = 0.0;
    double max_joint_error_rad = 0.0;
    double max_bound_excess_rad = 0.0;
    double max_lateral_speed_mps = 0.0;
    double max_lateral_drift_mps = 0.0;
    std::array<double, 2> min_joint_rad{1e9, 1e9};    // p6, p7 (ground truth)
    std::array<double, 2> max_joint_rad{-1e9, -1e9};
    // ∫ x dt over the phase (x: the truth's forward position from the run's start), and the
    // time it covers, for the mean forward position.
    double forward_integral_m_s = 0.0;
    double forward_time_s = 0.0;
    double last_time_s = 0.0;
  };

  Snapshot snapshot(const Session& session, double time_s) const;
  double joint_error_rad(const sim::GroundTruth& truth) const;
  void observe_phases(const Session& session, double time_s, double forward_m,
                      std::optional<double> voltage_drop_v,
                      double joint_error_rad, double bound_excess_rad,
                      const std::array<double, 2>& joint_rad, double lateral_speed_mps,
                      std::optional<double> lateral_drift_mps);
  void add_phase_metrics(const PhaseWindow& window, const Snapshot& end,
                         std::map<std::string, double>& metrics) const;

  const Params* params_;
  std::vector<PhaseWindow> phases_;
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
  double max_roll_rad_ = 0.0, max_pitch_rad_ = 0.0;  // |roll|, |pitch| of the truth
  double max_lateral_speed_mps_ = 0.0;
  SidewaysDrift sideways_drift_;
  double max_lateral_drift_mps_ = 0.0;
  double tip_over_faults_ = 0.0, stuck_faults_ = 0.0, joint_blocked_faults_ = 0.0;
  double first_tip_over_s_ = -1.0, first_stuck_s_ = -1.0, first_joint_blocked_s_ = -1.0;
  double other_faults_ = 0.0;
  bool tip_over_latched_ = false, stuck_latched_ = false;
  std::size_t joints_blocked_ = 0;  // "front/rear joint blocked" faults latched the cycle before
  double max_joint_stall_s_ = 0.0;
  // Missions (core/navigation): counted as the driver's status shows them.
  std::uint64_t last_mission_id_ = 0;
  navigation::MissionState last_mission_state_ = navigation::MissionState::kIdle;
  double missions_started_ = 0.0, missions_reached_ = 0.0, missions_aborted_ = 0.0;
  double mission_corrections_ = 0.0, final_mission_progress_ = 0.0;
  void observe_missions(const navigation::MissionStatus& mission);
  // Odometry: the truth in the frame of the driver's last (re)start, and the wheel odometry since.
  estimation::OdometryFrameTracker truth_odometry_;
  bool odometry_started_ = false;
  double odometry_origin_path_m_ = 0.0;
  std::array<double, 3> wheel_pose_{};  // x, y, ψ
  void observe_odometry(const Session& session);
  void add_odometry_metrics(const Session& session, std::map<std::string, double>& m) const;
  bool was_timed_out_ = true;
  double faults_ = 0.0;
  double malformed_ = 0.0;
  std::optional<double> stop_mark_s_;
  double last_motion_s_ = 0.0;
  double last_duty_s_ = 0.0;
  std::optional<double> front_target_rad_, rear_target_rad_;
};

}  // namespace marsokhod::runner
