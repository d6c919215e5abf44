// The driver: one deterministic control cycle (the thesis' Joyride), the same on the rover, in
// the simulator and in replay. Each call of step() is one cycle of docs/architecture.md:
//   1.–2. the frames that arrived since the last cycle (responses to the last requests) are
//         decoded and sorted; missing, duplicated and malformed ones are counted;
//   3.    tracking (3.2)–(3.5), backlash, ν and load;
//   4.–6. behaviours, control laws, gaits, summation → duty cycles (MotionController);
//   7.    the duty-cycle rules of chapter 3.2, then the next requests, encoded, and the status.
// Time comes in as a value; there are no clocks, threads or I/O here.
//
// Safety: no valid operator input for operator_timeout_s ⇒ zero targets and a controlled stop
// (ramps and the slew limit bring every motor to d = 0). A controller silent for
// missed_responses_limit cycles latches a fault that stops the rover until the operator clears
// it (OperatorInput::clear_faults) and every controller answers again. Invalid operator inputs
// are rejected with a reason and the last valid one stands until the timeout.
//
// Restarts (joint_memory.hpp): joint_memory() is what to keep of the joints after each cycle; a
// driver constructed with it continues p̄ from there instead of taking the joints vertical, and
// runs Procedure 4.3's motion where they stand to take up the gaps (p = p̄). If the
// controllers' registers do not continue the kept state, the joints are unknown: the driver
// drives the wheels but holds the joints (no gait, no joint command, no behaviour moves them)
// and says so in its warnings until the operator sets them vertical in calibration mode and
// leaves it (Procedure 4.3 by hand, docs/gamepad.md).
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "core/params.hpp"
#include "core/protocol/can_frame.hpp"
#include "core/tracking/motor_tracker.hpp"
#include "core/tracking/sensor_tracker.hpp"
#include "driver/frame_intake.hpp"
#include "driver/joint_memory.hpp"
#include "driver/motion_controller.hpp"
#include "driver/operator_channel.hpp"
#include "driver/startup.hpp"
#include "core/estimation/null_drift.hpp"
#include "core/navigation/mission.hpp"
#include "driver/status.hpp"

namespace marsokhod::driver {

class Driver {
 public:
  // `kept`: the joint state a previous driver left (a restart); none: a first start.
  explicit Driver(const Params& params, std::optional<JointMemory> kept = std::nullopt);

  // One cycle at time t [s] (strictly increasing). `received`: every frame seen on the bus since
  // the previous step. `input`: the operator's newest message, if one arrived this cycle.
  // Returns the requests to send now, in order µ0…µ7, then µ8.
  const std::vector<protocol::CanFrame>& step(double time_s,
                                              std::span<const protocol::CanFrame> received,
                                              const OperatorInput* input = nullptr);

  const DriverStatus& status() const { return status_; }
  const RuntimeSettings& runtime() const { return runtime_; }
  // Throws std::invalid_argument (see validate(RuntimeSettings)); nothing changes then.
  void set_runtime(const RuntimeSettings& settings);
  // What to keep of the joints after this cycle for a restart: none before Procedure 4.3 has
  // ended (a restart runs it again); JointMemory::known = false while they are unknown; the
  // state this driver was given until it has judged it.
  std::optional<JointMemory> joint_memory() const;

 private:
  void take_responses(const CycleResponses& responses);
  void update_faults(const OperatorInput* input);
  MotionInput motion_input(double period_s) const;
  MotorVector wanted_duties(double time_s, const MotionInput& input);
  void reset_joint_positions(std::array<double, 2> dragged_rad = {});
  void take_kept_joints();  // a restart: the kept state against the joints' first readings
  void hold_unknown_joints();
  void take_up_joint_gaps();
  void encode_requests();
  std::string lcd_text() const;
  void update_pose(double period_s);
  void update_mission(double time_s);  // cmd_vel and missions (core/navigation/mission.hpp)
  void update_failsafes(double period_s);  // tip-over and stuck (core/estimation/failsafes.hpp)
  bool on_slope() const;  // the accelerometer off the vertical by more than the slant dead band

  const Params* params_;
  FrameIntake intake_;
  Startup startup_;
  tracking::AllMotorsTracker motors_;
  tracking::SensorTracker sensors_;
  OperatorChannel operator_;
  MotionController motion_;
  estimation::PoseEstimator pose_;
  estimation::TipOverMonitor tip_over_;
  estimation::StuckMonitor stuck_;
  estimation::JointBlockedMonitor joint_blocked_;
  navigation::MissionRunner missions_;
  estimation::NullDriftCorrection null_drift_;
  estimation::PoseCorrection pose_correction_;  // from this cycle's gyro reading, for update_pose
  bool pose_started_ = false;            // update_pose has begun the odometry
  // The last gyro reading came while every motor was off and at rest: the rover cannot turn, and
  // the dead reckoning takes its heading as held (a zero-velocity update, update_pose).
  bool gyro_still_ = false;
  // The motors' measured speeds over the last kStillCycles cycles (a ring): a motor stands when
  // their mean, not one sample, is below the still speed (take_responses).
  static constexpr std::size_t kStillCycles = 8;
  std::array<MotorVector, kStillCycles> recent_velocity_radps_{};
  std::size_t recent_velocities_ = 0;  // how many cycles the ring has seen
  std::uint64_t attitude_readings_ = 0;  // µ8's readings the tip-over monitor has seen
  RuntimeSettings runtime_;
  DriverStatus status_;
  mobility::OperatorTargets targets_;
  MotorVector position_offset_rad_{};  // Procedure 4.3 re-zeroes the joints' p̄
  // The trackers' uncertainty_counts() when p̄ was last set (Procedure 4.3, a kept state), and
  // the uncertainty a kept state brought along
  std::array<std::uint64_t, kMotorCount> uncertainty_origin_counts_{};
  MotorVector uncertainty_carried_rad_{};
  MotorVector duty_{};
  std::array<bool, kMotorCount + 1> expected_{};
  std::optional<double> start_time_s_;
  double last_time_s_ = 0.0;
  bool was_calibrating_ = false;
  bool startup_calibrated_ = false;
  std::optional<JointMemory> kept_;  // until the joints' first readings judge it
  bool joints_restored_ = false;     // a kept state continued: take up the gaps, keep p̄
  bool positions_known_ = false;     // p̄ known: after Procedure 4.3, or continued
  bool stopping_ = false;  // the operator's stop or timeout is in force
  std::vector<protocol::CanFrame> requests_;
};

}  // namespace marsokhod::driver
