// The start-up sequence of the driver, before any driving:
//   1. configure every motor controller: 0xi2 with icr (511), pwm = 0 and con, repeated each
//      cycle until µi answers 0xi3 (icr changes only while pwm = 0, chapter 3.2);
//   2. enable µ8's dead man's switch: 0x82 with dog, repeated until 0x83;
//   3. Procedure 4.3: both joint motors at d = −calibration_duty until each shaft has crossed
//      its backlash gap toward the negative end (at most 3 s), then at rest until both shafts
//      have stopped, then the joint positions are set to Remark 3.1's p̄⁰ = p⁰ (−1.2121,
//      +1.2121) less how far each shaft dragged its joint after they met (over_travel_rad();
//      the driver keeps p inside (5.3)) — set after the stop, so that no coasting is left to
//      shift them. A shaft has crossed its gap when it meets its joint: the joint's weight
//      slows it below half the no-load speed ν of its duty (measured: 0.13–0.15 rad/s free,
//      0.03–0.04 rad/s dragging the joint at d = −0.08 on hard ground), once ν has settled
//      (kEngagementSettle_s), or below
//      kMetSpeedShare of its own free speed in the gap: on soft soil the wheels give way and the
//      shaft drags its joint at 0.10–0.13 rad/s, which ν/2 found 0.1 s (0.01 rad) late. The
//      drag is counted from the shaft's last free reading. Travelling the configured b instead,
//      as the thesis words it, drags the joint on by b − b_t on a unit whose true gap b_t is
//      narrower (the rear joint out of (5.3) by up to 0.0375 rad), or stops short of the gap's
//      end on a wider one; the measured meeting holds on every unit. If the
//      shaft never slows it stops after (1 + joints.backlash_uncertainty)·b, the widest gap —
//      but on a slope (the accelerometer off the vertical by more than the slant dead band)
//      after (1 − backlash_uncertainty)·b, the narrowest: there gravity may aid the shaft into
//      its joint (the lock then brakes the joint at the motor's own speed, and nothing slows),
//      and going on would drag the joint out of (5.3). The limits that keep a joint inside
//      (5.3) — that one and a restart's p̄ − p_min, below — are anticipated by the shaft's run-on
//      after the decision, |w̄|·(dead time + h): on the soft sand a restarted shaft dragging its
//      joint ran on 0.008 rad past p̄ − p_min (the hour's soak, seed 1: the rear joint 0.0103
//      rad out of (5.3)). Stopping short leaves the driver's p
//      below the truth by at most 2·uncertainty·b, on the safe side of the negative bounds, and
//      exactly uncertainty·b above it on the positive side, which joint_margin.hpp covers;
//   4. driving.
// A driver restarted with a kept joint state (joint_memory.hpp) waits in phase 3 with the joints
// at rest until it has judged that state against the joints' first readings (take_joints()),
// then runs the same motion: each shaft takes up its gap toward the negative end where the joint
// stands, bent or not. The kept state gives p̄ there; the motion gives p = p̄ — a joint the
// brown-out's abrupt stop let swing through its gap is found again. A bent joint may stand at
// its negative bound (a gait's stroke ends there) with its shaft already engaged, so that the
// shaft never slows and would drag the joint out of (5.3) by the widest gap: there the shaft
// travels at most p̄ − p_min (take_joints' max_travel_rad), which keeps the joint inside
// whatever end of the gap the shaft stood at; a shaft stopped short leaves p = p̄ at most that
// far above the truth, on the safe side of the negative bound (for a joint inside (5.3)). A
// shaft at rest shows no speed to anticipate its run-on by, and one just started reads slower
// than the duties already sent will turn it: so the run-on a travel limit anticipates is at
// least that of the calibration duty's free speed (free_run_on_rad()), and a take-up allowed
// less than that does not start at all (take_up_skipped()). Seed 8's two-hour soak had a
// restarted rear shaft allowed 0.0014 rad run 0.0054, taking its joint from 0.0051 to 0.0093 rad
// out of (5.3). A take-up not started leaves p = p̄, as a shaft stopped short does.
// Pure: the phase advances on the responses it is shown and on time given as a value.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "core/params.hpp"

namespace marsokhod::driver {

enum class StartupPhase : std::uint8_t { kConfigure, kEnableDeadMan, kCalibrate, kDone };
std::string_view phase_name(StartupPhase phase);

inline constexpr double kCalibrationTimeout_s = 3.0;  // Procedure 4.3: "in no more than 3 s"
inline constexpr double kShaftStoppedRadps = 0.005;   // a shaft this slow has stopped
// ν of (4.4) follows a duty step within its δ table (5 cycles, one late: 0.094 s at 64 Hz) and
// the motor's lag; before that w̄ < ν/2 says nothing.
inline constexpr double kEngagementSettle_s = 0.15;
inline constexpr double kEngagedSpeedShare = 0.5;  // w̄ below this share of ν: the gap is closed
// The crossing's own speed: |w̄| at or above this share of its mean so far is the shaft still
// free (the readings scatter by ±2.5 %, a count of 0.0017 rad/s at 0.15 rad/s) ...
inline constexpr double kFreeSpeedShare = 0.92;
// ... and below this share, after kMinFreeSamples free readings, the shaft has met its joint.
inline constexpr double kMetSpeedShare = 0.85;
inline constexpr int kMinFreeSamples = 3;

class Startup {
 public:
  explicit Startup(const Params& params);

  StartupPhase phase() const { return phase_; }
  bool configured(std::size_t motor) const { return configured_.at(motor); }

  // Phase 3 without Procedure 4.3: the joints come from a kept state (see above).
  void continue_joints() { continue_joints_ = true; }
  bool continues_joints() const { return continue_joints_; }
  // The kept state was judged (restored or refused): phase 3's motion may begin, each shaft
  // travelling at most max_travel_rad (front, rear) toward the negative end (see above).
  void take_joints(std::array<double, 2> max_travel_rad = {kNoTravelLimit, kNoTravelLimit});
  static constexpr double kNoTravelLimit = 1e9;
  // How far a shaft at the calibration duty's free speed runs on after a decision to stop it,
  // front and rear: its no-load speed by (4.3) at the nominal supply (a full battery's higher
  // voltage turns it a few per cent faster), over the dead time and a cycle; about what a shaft
  // started from rest runs before its readings can stop it.
  std::array<double, 2> free_run_on_rad() const { return free_run_on_rad_; }
  // After take_joints: whether the joint's (front, rear) take-up was allowed less than that
  // and does not start.
  bool take_up_skipped(std::size_t joint) const { return take_up_skipped_.at(joint); }
  // What take_joints allowed the joint (front, rear), skipped or not.
  double take_up_travel_rad(std::size_t joint) const { return take_up_allowed_rad_.at(joint); }

  // Phase 1: the controllers that answered 0xi3 this cycle.
  void on_configured(std::size_t motor);
  // Phase 2: µ8 answered 0x83.
  void on_dead_man_acknowledged();
  // Phase 3, every cycle: the measured shaft positions p̄6, p̄7, speeds w̄6, w̄7 and the no-load
  // speeds ν6, ν7 of (4.4) at time t. Returns the joint duty cycles to apply (0 once a joint's
  // gap is closed). Starts timing on the first call.
  std::array<double, 2> calibrate(double time_s, const std::array<double, 2>& shaft_rad,
                                  const std::array<double, 2>& shaft_speed_radps,
                                  const std::array<double, 2>& no_load_speed_radps,
                                  bool on_slope = false);

  // How far each shaft travelled toward the negative end after it met its joint (≥ 0): the
  // joint went with it, from where Remark 3.1 has it (p̄⁰) to p̄⁰ − over_travel. 0 for a shaft
  // that stopped without meeting its joint (the travel limits above).
  std::array<double, 2> over_travel_rad() const;

 private:
  void advance();

  const Params* params_;
  double run_on_s_;  // a shaft's run-on after a decision to stop it: the dead time + a cycle
  std::array<double, 2> free_run_on_rad_{};
  std::array<bool, 2> take_up_skipped_{};
  std::array<double, 2> take_up_allowed_rad_{kNoTravelLimit, kNoTravelLimit};
  StartupPhase phase_ = StartupPhase::kConfigure;
  std::array<bool, kMotorCount> configured_{};
  bool continue_joints_ = false;
  bool joints_taken_ = false;
  bool calibration_started_ = false;
  double calibration_start_s_ = 0.0;
  std::array<double, 2> shaft_start_rad_{};
  std::array<bool, 2> gap_closed_{};
  std::array<double, 2> max_travel_rad_{kNoTravelLimit, kNoTravelLimit};
  // The crossing's free speed: the mean |w̄| of its free readings and their count; the shaft's
  // position at the last free reading (where it met its joint, once it has slowed); the latest.
  std::array<double, 2> free_speed_sum_{};
  std::array<int, 2> free_samples_{};
  std::array<double, 2> free_shaft_rad_{};
  std::array<bool, 2> met_{};
  std::array<double, 2> last_shaft_rad_{};
};

}  // namespace marsokhod::driver
