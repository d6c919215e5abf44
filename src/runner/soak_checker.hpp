// The soak's invariants (`marsokhod soak`, RELIABILITY.md), checked every cycle by a pure class
// fed what the cycle left behind: the driver's status, the frames it received and sent, and the
// simulator's truth. No I/O, no clocks: unit-tested with hand-made cycles.
//
//   finite          no NaN or Inf in any number of the status
//   duty-bound      |d| ≤ 1 and |d| ≤ D (6.3) — where the duty-step rule forbids reaching D in
//                   one cycle (D may fall by more than a step), d must move toward it by a full
//                   step: |d^k| ≤ max(D^k, |d^(k−1)| − step). Duties are those of the requests
//                   sent, pwm/icr; half a pwm count is the register's resolution.
//   duty-step       |pwm^k − pwm^(k−1)| ≤ round(step·icr) counts (chapter 3.2), and a request that
//                   toggles drv carries |d| ≤ direction_change_duty (+ half a count)
//   joint-bounds    the joints themselves (truth) inside (5.3) by ≤ joint_tolerance_rad, every
//                   cycle: also while the driver is down with the computer (a brown-out), when
//                   the motors run on at their last duties for µ8's delay (the driver limits
//                   its joint commands near the bounds for that run-on, joint_margin.hpp), and
//                   after it (the restarted driver continues from the kept joint state,
//                   driver/joint_memory.hpp). The farthest excess while the driver was down is
//                   reported apart (max_down_joint_excess_rad). A joint whose encoder lost
//                   pulses since the first driver started is judged by the driver's own
//                   estimate p instead: the driver cannot know the truth then (lost pulses are
//                   not detected — RELIABILITY.md), once its start-up has set p⁰ (not while it is
//                   down); how far the truth went out then is reported apart
//                   (max_unknown_joint_excess_rad)
//   missed-counted  the status' bus.missed equals the missing responses counted here from the
//                   frames (a controller sent a request in the previous cycle and did not answer)
//   silent-reported "µN silent" is in the faults by the cycle µN's answer has been missing for
//                   missed_responses_limit cycles in a row (docs: latched after 3 cycles)
//   fault-stop      in fault mode every |d| falls by a full step each cycle until 0
//   operator-stop   the operator silent for operator_timeout_s (Field Experiment 6.7): the driver
//                   brings the rover to a controlled stop that ends with every d = 0 exactly,
//                   within the stop's own time from then on: the slowest ramp of (4.14) to rest
//                   (a joint at its full C braking with −C: ln 2/μ_joint = 1.73 s; the wheels
//                   ln 2/μ_drive = 0.35 s), then the duties' fall by max_duty_step a cycle from
//                   at most 1 (20 cycles), and a cycle each for the sampled landings. The duty
//                   step rule of chapter 3.2 forbids a jump to 0, so "off at the timeout" cannot
//                   hold; off by timeout + 2.1 s, and staying off, can. Not in start-up:
//                   Procedure 4.3 moves the joints on its own, as docs say
//   dead-man        the driver down (brown-out): µ0–µ7's duties are 0 from its last requests +
//                   0.262144·dog s + one cycle on; µ8 repeats its stop frames every 0.262144 s
//                   while the silence lasts, so for µi the deadline moves by 0.262144 s for each
//                   of µ8's frames to µi that the bus lost since (the simulator counts them: the
//                   check holds µ8 to stopping µi with the first stop frame that arrives)
//   restart         a driver that comes back starts afresh: start-up mode, cycle 1, only
//                   configuration requests to µ0–µ7
//   supply-warning  the supply µ8 reported (its vcc on the bus, by Procedure 3.5's conversion)
//                   below brownout_v + 0.5 V in 3 readings in a row ⇒ a "supply … near the
//                   brown-out voltage" warning. The rule starts from µ8's reading, not the
//                   truth: µ8 samples once a cycle, and under a sagging battery the true supply
//                   moves by tenths of a volt between samples
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/params.hpp"
#include "core/protocol/can_frame.hpp"
#include "core/protocol/codec.hpp"
#include "driver/status.hpp"

namespace marsokhod::runner {

enum class Invariant : std::uint8_t {
  kFinite,
  kDutyBound,
  kDutyStep,
  kJointBounds,
  kMissedCounted,
  kSilentReported,
  kFaultStop,
  kOperatorStop,
  kDeadMan,
  kRestart,
  kSupplyWarning,
};
inline constexpr std::size_t kInvariantCount = 11;
const char* invariant_name(Invariant invariant);  // "duty-bound", …

struct Violation {
  Invariant invariant = Invariant::kFinite;
  std::int64_t time_us = 0;  // the session's t_k
  std::string detail;        // "µ3 d = 0.4521 above D = 0.3000 (previous 0.4110)"
};

struct CheckerLimits {
  double duty_ceiling = 1.0;          // the "≤ 1" of duty-bound (tests force violations with less)
  double joint_tolerance_rad = 0.01;  // the "inside (5.3) by ≤ 0.01 rad"
  int supply_cycles = 3;              // "reported within 3 cycles"
};

// One cycle as the checker sees it.
struct CycleView {
  std::int64_t time_us = 0;
  bool driver_running = true;
  const driver::DriverStatus* status = nullptr;  // required while the driver runs
  std::span<const protocol::CanFrame> received;  // delivered to the driver before its step
  std::span<const protocol::CanFrame> sent;      // its requests
  bool operator_command = false;  // any input that renews the timeout arrived this cycle
  std::array<double, 2> joint_angle_rad{};      // truth: p6, p7
  MotorVector motor_duty{};                      // truth: what µ0–µ7 apply now
  double supply_v = 24.0;                        // truth (for the report only)
  std::array<bool, 2> joint_encoder_fault{};     // µ6, µ7 losing pulses this cycle
  // truth: µ8's frames to µ0–µ7 the bus lost so far (a running count, never reset)
  std::array<std::uint64_t, kMotorCount> stop_frames_lost{};
};

class InvariantChecker {
 public:
  explicit InvariantChecker(const Params& params, CheckerLimits limits = {});

  // Checks one cycle (cycles in order, one period apart); returns its violations.
  std::vector<Violation> check(const CycleView& cycle);
  // Invariants evaluated so far (each applicable invariant once a cycle).
  std::uint64_t evaluations() const { return evaluations_; }
  // The largest distance of a joint outside (5.3) seen so far (0 inside), as joint-bounds judges.
  double max_joint_excess_rad() const { return max_joint_excess_rad_; }
  // Where that largest excess was, once it is above 0: the cycle's t_k and joint_bounds' detail
  // ("rear joint 2.5561 rad is 0.0061 rad outside (5.3) [...]", and whether the driver was down).
  const std::optional<Violation>& max_joint_excess_at() const { return max_joint_excess_at_; }
  // The truth's farthest excess over (5.3) of a joint the driver could not know (see above).
  double max_unknown_joint_excess_rad() const { return max_unknown_joint_excess_rad_; }
  // The largest excess over (5.3) of a (known) joint while the driver was down.
  double max_down_joint_excess_rad() const { return max_down_joint_excess_rad_; }

 private:
  struct SentDuty {
    int signed_pwm = 0;  // (−1)^drv · pwm; a configuration request counts as 0
    bool drv = false;
  };
  using Report = std::vector<Violation>;
  void add(Report& out, Invariant invariant, const CycleView& c, std::string detail);
  std::array<SentDuty, kMotorCount> sent_duties(const CycleView& c) const;
  std::array<bool, kMotorCount + 1> answered(const CycleView& c) const;
  std::optional<double> reported_supply_v(const CycleView& c) const;
  void check_finite(const CycleView& c, Report& out);
  void check_duties(const CycleView& c, const std::array<SentDuty, kMotorCount>& d, Report& out);
  void check_joints(const CycleView& c, Report& out);
  void check_responses(const CycleView& c, Report& out);
  void check_operator_stop(const CycleView& c, const std::array<SentDuty, kMotorCount>& d,
                           Report& out);
  void check_driver_down(const CycleView& c, Report& out);
  void check_joints_down(const CycleView& c, Report& out);
  void check_restart(const CycleView& c, Report& out);
  void check_supply(const CycleView& c, std::optional<double> reported_v, Report& out);
  // max_joint_excess_rad_ and where, when excess passes it.
  void note_joint_excess(const CycleView& c, double excess, std::string detail);

  const Params* params_;
  CheckerLimits limits_;
  protocol::DecodeContext context_;
  std::int64_t cycle_us_;
  std::int64_t stop_allowance_us_;  // timeout + the controlled stop's time (operator-stop)
  std::uint64_t evaluations_ = 0;
  double max_joint_excess_rad_ = 0.0;
  std::optional<Violation> max_joint_excess_at_;  // invariant kJointBounds, the excess' cycle
  double max_unknown_joint_excess_rad_ = 0.0;
  double max_down_joint_excess_rad_ = 0.0;
  bool previous_running_ = false;
  bool ever_ran_ = false;
  std::array<SentDuty, kMotorCount> previous_{};
  std::array<int, kMotorCount + 1> missing_{};  // consecutive cycles without an answer
  std::uint64_t missed_total_ = 0;              // since the driver started
  std::optional<std::int64_t> last_command_us_;
  std::optional<std::int64_t> last_running_us_;
  std::array<std::uint64_t, kMotorCount> stop_frames_lost_then_{};  // at last_running_us_
  std::array<bool, 2> encoder_faulted_{};       // since the first driver started
  int low_supply_cycles_ = 0;
};

}  // namespace marsokhod::runner
