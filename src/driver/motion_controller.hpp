// Steps 3–6 of the control cycle (docs/architecture.md) while driving: from the tracked motor
// positions and velocities, the supply voltage, the accelerometer and the operator's targets to
// the duty cycles the motors should get.
//   3. backlash (4.1)/(4.2) → p, w; no-load estimate (4.4) → ν, load l = w − ν
//   4. behaviours (chapter 6): D (6.3), slope σ and joint bounds (6.4), contract on turn,
//      axle placement, load distribution h
//   5. (4.14) ramps v1…v4 (v3: m3); (4.16) or a gait's (4.15) moves the joints; ϱ and ρ (Remark 5.5)
//   6. summation (5.4) with κ under (5.5); + h; + the slope hold; (4.3) inverse → duty cycles
// The duty-cycle rules (slew limit, drv at pwm ≈ 0) and the CAN encoding come after, in Driver.
#pragma once

#include <array>
#include <optional>

#include "core/adaptation/backlash.hpp"
#include "core/adaptation/motor_curve.hpp"
#include "core/adaptation/no_load_estimator.hpp"
#include "core/behaviour/axle_placement.hpp"
#include "core/behaviour/power_management.hpp"
#include "core/behaviour/slant_response.hpp"
#include "core/behaviour/slope_hold.hpp"
#include "core/behaviour/slope_estimate.hpp"
#include "core/behaviour/switches.hpp"
#include "core/mobility/axle_placement.hpp"
#include "core/mobility/gait_sequencer.hpp"
#include "core/mobility/gamepad.hpp"
#include "core/params.hpp"
#include "driver/operator_commands.hpp"
#include "driver/status.hpp"

namespace marsokhod::driver {

struct MotionInput {
  double period_s = 0.0;
  MotorVector shaft_position_rad{};   // p̄ (calibration offsets applied)
  MotorVector shaft_velocity_radps{}; // w̄
  // How far p̄ may be off for what the encoder registers hid since Procedure 4.3
  // (motor_position.hpp): no command pushes a joint further out than its bounds narrowed by as
  // much at both ends
  MotorVector position_uncertainty_rad{};
  double supply_v = 24.0;             // U
  double reference_supply_v = 0.0;    // Ū (Procedure 3.5); 0 until µ8 has answered
  std::array<double, 3> accel_mps2{0.0, 0.0, -9.81};
  mobility::OperatorTargets targets;
  // A controlled stop (operator timeout or stop): every motion ramps to rest with (4.14), no
  // joint is moved back into its bounds and no load is redistributed, and once all are at rest
  // every wanted duty is exactly 0 — the motors are off, not idling in their dead zone.
  bool stopping = false;
};

class MotionController {
 public:
  explicit MotionController(const Params& params);

  // Procedure 4.3's end: the joints' p = p̄ = Remark 3.1's positions; history cleared. A
  // restart continuing from a kept state (joint_memory.hpp) gives each joint's p instead.
  void reset_joint_positions(const MotorVector& position_rad);
  // p of (4.1) for the eight motors, as the last cycle left it.
  MotorVector joint_positions() const { return backlash_.joint_position_rad(); }
  // ν of (4.4) on what was sent less the slope hold's term: the speeds the plan asked for. The
  // stall check counts these: a wheel the hold keeps still on a slope is doing what it was asked.
  MotorVector planned_no_load_velocity() const {
    return plan_estimator_.no_load_velocity_radps();
  }

  // One driving cycle: the duty cycles wanted (before the slew rules); fills `status`.
  MotorVector update(const MotionInput& input, const RuntimeSettings& settings,
                     DriverStatus& status);

  // Tracking only (start-up, calibration, faults): backlash, ν and l, no control.
  void observe(const MotionInput& input, DriverStatus& status);

  // Field Experiment 1.1: the supply's current [A] the duty cycles `duty` could draw at most, every
  // motor stalled, at this cycle's speeds and voltage (core/behaviour/supply_current.hpp).
  double supply_current_bound_a(const MotorVector& duty, const MotionInput& input) const;

  // The duty cycles actually sent (after the slew rules): ŵ^k = ζW(d)U/Ū (4.3) with Ū the
  // nominal 24 V, remembered for (4.4); d^k for (6.3).
  void record_sent(const MotorVector& duty, double supply_v);

 private:
  struct JointCommands;
  void track(const MotionInput& input, DriverStatus& status);
  JointCommands stopping_joint_commands();
  bool at_rest() const;
  // p + v·dead time: where the joint will be when this cycle's command acts (joint_dead_time_s).
  double predicted_joint_position(std::size_t motor, const DriverStatus& status) const;
  behaviour::JointBounds with_backlash_margin(behaviour::JointBounds bounds,
                                              const DriverStatus& status) const;
  // The bounds less the joints' position uncertainty at both ends (to the middle at most).
  static behaviour::JointBounds narrowed_by_uncertainty(behaviour::JointBounds bounds,
                                                        const DriverStatus& status);
  JointCommands joint_commands(const MotionInput& input, const RuntimeSettings& settings,
                               DriverStatus& status);
  // Step 4's parts: D of (6.3); σ and the joint bounds (6.4) with the backlash margin.
  void update_duty_bound(const MotionInput& input, const RuntimeSettings& settings,
                         DriverStatus& status);
  behaviour::JointBounds update_slope_and_bounds(const MotionInput& input,
                                                 const RuntimeSettings& settings,
                                                 DriverStatus& status);
  // The joints' commands kept inside `bounds`, axle placement, and the walking motion of (5.4).
  MotorVector walking_motion(JointCommands joints, const behaviour::JointBounds& bounds,
                             const MotionInput& input, const RuntimeSettings& settings,
                             DriverStatus& status);
  MotorVector ramp_driving(const MotionInput& input, const RuntimeSettings& settings,
                           DriverStatus& status);
  MotorVector to_duty(const MotorVector& w_hat, const MotionInput& input) const;

  const Params* params_;
  adaptation::MotorCurve curve_;
  const LoadGainParams* load_gains_;  // B± of (4.6) at the configured icr
  adaptation::RoverBacklashTracker backlash_;
  adaptation::NoLoadEstimator estimator_;
  // (4.4) on the commands less the slope hold's term: ν̂ of the plan (slope_hold.hpp).
  adaptation::NoLoadEstimator plan_estimator_;
  behaviour::SlopeHold slope_hold_;
  MotorVector hold_radps_{};  // the slope hold's share of this cycle's ŵ (within its bounds)
  // The wheels' roles the slope hold's lost angle belongs to: the gait, its state and whether
  // 6.2.3 has switched each joint's axle placement (none before the first cycle).
  struct HoldRole {
    mobility::Gait gait = mobility::Gait::kNone;
    std::optional<std::size_t> gait_state;
    bool front_switched = false;
    bool rear_switched = false;
    bool operator==(const HoldRole&) const = default;
  };
  HoldRole hold_role_{};
  bool gait_running_ = false;  // a gait drives the joints this cycle
  JointParams joints_;  // (5.3) with the full backlash margin, for the gaits' strokes
  double joint_dead_time_s_;
  // T_run of the dead man's run-on (joint_margin.hpp): 0.262144·dog s + the dead time; 0 with
  // the switch off.
  double run_on_s_;
  mobility::GaitSequencer gait_;
  mobility::DrivingIntent intent_ = mobility::DrivingIntent::kForward;
  behaviour::SlopeEstimate slope_;
  behaviour::AxlePlacementState front_placement_;
  behaviour::AxlePlacementState rear_placement_;
  std::array<double, 4> drive_velocity_{};  // v1, v2, v3, v4 after (4.14)
  // v6, v7: the joints' velocity states of (4.13), i.e. the ŵ6(t), ŵ7(t) assigned to the joint
  // motors (chapter 4.4). The measured joint velocity cannot serve: it is 0 while a shaft
  // crosses its backlash gap, and the law would never leave the gap.
  std::array<double, 2> joint_velocity_{};
  MotorVector last_duty_{};
  // The last cycle's D_I on the tether: where its search starts. The same answer as a fresh
  // bisection where the stall bound grows with D; where it dips, an admitted D that may differ
  // from the bisection's and depends on the cycles before (supply_current.hpp).
  double last_current_duty_bound_ = 1.0;
  MotorVector load_{};
  MotorVector velocity_{};  // w of (4.2)
  behaviour::MeasuredDropExcess drop_excess_;  // what (4.5) leaves out of the measured drop
};

}  // namespace marsokhod::driver
