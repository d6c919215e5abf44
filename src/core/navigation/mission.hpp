// Commands for application software (Quote 2.3: the Ames operators drove by dead reckoning,
// "turn to a given heading relative to the current heading and then move a certain distance"):
// cmd_vel, and missions the driver runs through the elementary motions m1 (drive) and m2 (spin)
// of chapter 5, closed around the pose estimate (core/estimation/pose_estimator.hpp).
//
// cmd_vel — v [m/s] forward, ω [rad/s] counter-clockwise — onto m1 v1 + m2 v2 of (5.4), the
// centre wheels rolling:
//   v1 = v/r,   v2 = ω·(t/2)/r                         (r wheel radius, t track width)
// m2 runs the exterior wheels at F(c)·v2 so that they keep up with their longer way round the
// centre axle (Procedure 5.1). Skid steering drags the wheels sideways: the rover turns slower
// than ω (spin-efficiency scenario); the missions close the loop on the gyro's heading.
//
// Missions, each from the pose (x, y, ψ) where it starts:
//   turn Δψ    to ψ* = ψ₀ + Δψ on the spot (m2);
//   move d     along ψ₀ for d metres (m1; d < 0 backwards), holding the line;
//   goto W     to each waypoint of W in the odometry frame in turn: a turn on the spot towards
//              it when it lies more than turn_in_place_rad off the heading, then a move along the
//              leg (from the previous waypoint, or the start) to it.
// Per cycle, with e the heading still to turn and ρ the distance still to go along the leg:
//   turn:  v2 = sgn(e)·max(v2_min, min(v2_max, k_ψ·|e|, √(μ·|e|/g)))   g = r/(t/2)
//   move:  v1 = sgn(ρ)·max(v1_min, min(v1_cruise, √(μ·r·|ρ|)/r))
//          v2 = k_ψ·wrap(ψ_line − sgn(d)·atan(y_l/L) − ψ), |v2| ≤ v2_max/2
// μ is the ramp rate of (4.14) (operator.drive_rate_per_s): the ramp stops v1 within
// v1²/(2μ) and the profile above asks for half that deceleration, so the rover stops where the
// profile says. y_l is the rover's offset to the left of the leg's line, L the look-ahead: the
// heading aims back at the line L metres ahead (pure pursuit). A turn ends when e reaches 0 (its
// sign flips), a move when ρ ≤ the position tolerance (or its sign flips); then the targets are
// zero until the rover has stood still for settle_s (the gyro learns its null meanwhile, (3.4);
// a mission may ask for its own, MissionRequest::settle_s),
// and a leg that ended more than twice its tolerance off (the heading tolerance for a turn) is
// driven again (at most max_corrections times). A turn runs to its heading, not to the
// tolerance's near edge: on soft soil a stopped rover turns back as the wheels' soil unloads, and
// stopped at the edge it would end beyond twice the tolerance, every correction again. "Stood
// still": the driver judges the rover standing (every bridge off, every motor slower than its
// still threshold, the same judgement that feeds (3.4)) and |ω| < still_yaw_rate_radps. Not the
// pose's speed: its distance counts the centre unit's pitch, and the accelerometer's noise makes
// it read up to 1 cm/s at rest. No progress (e or ρ shrinking by less than 1 cm or 0.01 rad) for
// no_progress_s aborts the mission.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/estimation/pose_estimator.hpp"
#include "core/params.hpp"

namespace marsokhod::navigation {

enum class MissionKind { kNone, kVelocity, kTurn, kMove, kGoto };
enum class MissionState { kIdle, kRunning, kReached, kAborted };
std::string_view mission_kind_id(MissionKind kind);    // "none", "velocity", "turn", "move", "goto"
std::string_view mission_state_id(MissionState state);  // "idle", "running", "reached", "aborted"

struct Waypoint {
  double x_m = 0.0;
  double y_m = 0.0;
  bool operator==(const Waypoint&) const = default;
};

// The command's limits: |angle| ≤ 4π (two turns), |distance| ≤ 100 m, 1..64 waypoints within
// 1000 m of the odometry frame's origin.
inline constexpr double kMaxTurnRad = 12.566370614359172;
inline constexpr double kMaxMoveM = 100.0;
inline constexpr std::size_t kMaxWaypoints = 64;
inline constexpr double kMaxWaypointM = 1000.0;
// A mission's own standing time (MissionRequest::settle_s): 0 < settle_s ≤ 60 s.
inline constexpr double kMaxSettleS = 60.0;

// turn, move or goto, as the operator asks for it.
struct MissionRequest {
  MissionKind kind = MissionKind::kTurn;
  double angle_rad = 0.0;            // turn: + counter-clockwise
  double distance_m = 0.0;           // move: + forward
  std::vector<Waypoint> waypoints;   // goto
  // Any kind: stand this long before the first leg and after each (the gyro measures its null
  // meanwhile) instead of navigation.settle_s; the standing's limit, navigation.max_settle_s,
  // grows by as much. Longer standings measure the null better: a heading for mission time.
  std::optional<double> settle_s;
  bool operator==(const MissionRequest&) const = default;
};

// cmd_vel.
struct VelocityCommand {
  double v_mps = 0.0;      // forward
  double yaw_radps = 0.0;  // counter-clockwise
  bool operator==(const VelocityCommand&) const = default;
};

// The largest |v| and |ω| of a velocity command: r·v1ᵈ and r·v2ᵈ/(t/2) of the operator's
// limits (operator.max_drive_speed_radps, max_spin_speed_radps).
double max_velocity_mps(const Params& params);
double max_yaw_rate_radps(const Params& params);

// nullopt when the request is well formed and inside the limits above; else what is wrong,
// naming the field ("angle_rad", "waypoints[2].x_m").
struct RequestError {
  std::string field;
  std::string message;
};
std::optional<RequestError> check_request(const MissionRequest& request);
std::optional<RequestError> check_velocity(const VelocityCommand& command, const Params& params);

// v1, v2 of (5.4) for cmd_vel (above). Throws std::invalid_argument on a non-finite command.
struct DriveTargets {
  double v1_radps = 0.0;
  double v2_radps = 0.0;
};
DriveTargets velocity_targets(const VelocityCommand& command, const Params& params);

struct MissionStatus {
  std::uint64_t id = 0;  // missions started so far (the velocity stream counts once per start)
  MissionKind kind = MissionKind::kNone;
  MissionState state = MissionState::kIdle;
  std::string reason;              // aborted: why
  double progress = 0.0;           // 0..1
  std::size_t leg = 0;             // goto: the waypoint being driven to
  std::vector<Waypoint> waypoints; // goto's; move: its end point; turn: none
  std::optional<double> target_heading_rad;
  std::optional<double> remaining_m;
  std::optional<double> remaining_rad;
  int corrections = 0;             // legs driven again after they ended off
  double settle_s = 0.0;           // the standing after each leg (0 before any mission)
  double started_s = 0.0;
  std::optional<double> ended_s;
  bool operator==(const MissionStatus&) const = default;
};

class MissionRunner {
 public:
  // Throws std::invalid_argument (the field's name) unless the navigation parameters are valid
  // (validate(NavigationParams)) and r, t > 0.
  explicit MissionRunner(const Params& params);

  // Starts a mission from `pose` at time t; a running one is replaced (it ends "aborted:
  // replaced by a new mission"). The rover has stood still for stood_s before (the driver's
  // judgement); a mission first stands until that makes settle_s, so that the gyro's null is
  // measured before the first leg as after every other (core/estimation/null_drift.hpp). Throws
  // std::invalid_argument (check_request's message) and changes nothing for a bad request.
  void start(const MissionRequest& request, const estimation::Pose& pose, double time_s,
             double stood_s);
  // The velocity stream: the first command after anything else starts a "velocity" mission;
  // the next ones continue it.
  void follow_velocity(double time_s);
  // Ends a running mission: state aborted with the reason. Does nothing when none runs.
  void abort(std::string_view reason, double time_s);

  bool running() const { return status_.state == MissionState::kRunning; }
  bool driving_mission() const { return running() && status_.kind != MissionKind::kVelocity; }

  // One cycle of a running turn/move/goto: the targets v1, v2 from the newest pose; `stands`:
  // the driver judges the rover standing this cycle (above). Zero when no such mission runs.
  // Throws std::invalid_argument on a non-finite pose.
  DriveTargets update(const estimation::Pose& pose, double time_s, bool stands);

  const MissionStatus& status() const { return status_; }

 private:
  // kStand: before the first leg (first_phase_), until the rover has stood settle_s.
  enum class Phase { kStand, kTurn, kDrive, kSettle };
  bool stood_still(const estimation::Pose& pose, double time_s, bool stands);
  void begin_leg(const estimation::Pose& pose);
  void begin_turn(double target_heading_rad);
  void begin_drive(const estimation::Pose& pose);
  void end_leg(const estimation::Pose& pose, double time_s);
  void finish(MissionState state, std::string_view reason, double time_s);
  DriveTargets turn_targets(const estimation::Pose& pose);
  DriveTargets drive_targets(const estimation::Pose& pose);
  void update_progress(const estimation::Pose& pose);
  bool progressed(double error, double time_s);

  const Params* params_;
  NavigationParams nav_;
  double settle_s_ = 0.0;      // this mission's standing: its settle_s or navigation.settle_s
  double max_settle_s_ = 0.0;  // navigation.max_settle_s, longer by as much
  MissionStatus status_;
  MissionRequest request_;
  Phase phase_ = Phase::kSettle;
  Phase settled_from_ = Phase::kDrive;
  Phase first_phase_ = Phase::kDrive;
  // The leg: a line from `from` to `to` (move, goto), or a heading (turn).
  Waypoint from_{};
  Waypoint to_{};
  double line_heading_rad_ = 0.0;
  double direction_ = 1.0;         // +1 forward, −1 backward along the line
  double target_heading_rad_ = 0.0;
  std::optional<double> turn_sign_;  // the sign of e when the turn began: a flip is an overshoot
  double settle_since_s_ = 0.0;
  std::optional<double> still_since_s_;
  bool settle_started_ = false;
  double best_error_ = 0.0;        // the smallest remaining error so far in this phase
  double best_error_s_ = 0.0;      // when it last shrank by the progress step
  std::vector<double> leg_lengths_m_;
  double total_length_m_ = 0.0;
  double turn_total_rad_ = 0.0;
};

}  // namespace marsokhod::navigation
