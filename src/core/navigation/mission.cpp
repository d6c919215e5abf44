#include "core/navigation/mission.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "core/checks/checks.hpp"

namespace marsokhod::navigation {
namespace {

constexpr double kProgressStepM = 0.01;    // "progress": ρ shrinking by 1 cm …
constexpr double kProgressStepRad = 0.01;  // … or e by 0.01 rad

double wrap(double angle) {
  return std::remainder(angle, 2.0 * std::numbers::pi);  // (−π, π]
}

double sign(double x) { return x < 0.0 ? -1.0 : 1.0; }

std::string text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", value);
  return buffer;
}

std::optional<RequestError> bad(std::string field, std::string message) {
  return RequestError{field, field + ": " + message};
}

std::optional<RequestError> check_finite_within(const std::string& field, double value,
                                                double limit, const char* unit) {
  if (!std::isfinite(value)) return bad(field, "must be a finite number");
  if (std::abs(value) > limit) {
    return bad(field, text(value) + " is out of range; allowed −" + text(limit) + ".." +
                          text(limit) + " " + unit);
  }
  return std::nullopt;
}

void validate(const NavigationParams& n) {
  const auto positive = [](double v, const char* name) {
    if (!(std::isfinite(v) && v > 0.0)) {
      throw std::invalid_argument(std::string("navigation.") + name + " must be > 0");
    }
  };
  positive(n.cruise_speed_mps, "cruise_speed_mps");
  positive(n.min_speed_mps, "min_speed_mps");
  positive(n.max_spin_radps, "max_spin_radps");
  positive(n.min_spin_radps, "min_spin_radps");
  positive(n.heading_gain, "heading_gain");
  positive(n.look_ahead_m, "look_ahead_m");
  positive(n.heading_tolerance_rad, "heading_tolerance_rad");
  positive(n.position_tolerance_m, "position_tolerance_m");
  positive(n.turn_in_place_rad, "turn_in_place_rad");
  positive(n.settle_s, "settle_s");
  positive(n.still_yaw_rate_radps, "still_yaw_rate_radps");
  positive(n.max_settle_s, "max_settle_s");
  positive(n.no_progress_s, "no_progress_s");
  if (n.min_speed_mps > n.cruise_speed_mps) {
    throw std::invalid_argument("navigation.min_speed_mps must be ≤ cruise_speed_mps");
  }
  if (n.min_spin_radps > n.max_spin_radps) {
    throw std::invalid_argument("navigation.min_spin_radps must be ≤ max_spin_radps");
  }
  if (n.max_corrections < 0) {
    throw std::invalid_argument("navigation.max_corrections must be ≥ 0");
  }
}

}  // namespace

std::string_view mission_kind_id(MissionKind kind) {
  switch (kind) {
    case MissionKind::kNone: return "none";
    case MissionKind::kVelocity: return "velocity";
    case MissionKind::kTurn: return "turn";
    case MissionKind::kMove: return "move";
    case MissionKind::kGoto: return "goto";
  }
  return "none";
}

std::string_view mission_state_id(MissionState state) {
  switch (state) {
    case MissionState::kIdle: return "idle";
    case MissionState::kRunning: return "running";
    case MissionState::kReached: return "reached";
    case MissionState::kAborted: return "aborted";
  }
  return "idle";
}

double max_velocity_mps(const Params& params) {
  return params.geometry.wheel_radius_m * params.operator_input.max_drive_speed_radps;
}

double max_yaw_rate_radps(const Params& params) {
  return params.geometry.wheel_radius_m * params.operator_input.max_spin_speed_radps /
         (0.5 * params.geometry.track_width_m);
}

std::optional<RequestError> check_request(const MissionRequest& r) {
  if (r.settle_s && !(std::isfinite(*r.settle_s) && *r.settle_s > 0.0 &&
                      *r.settle_s <= kMaxSettleS)) {
    return bad("settle_s", (std::isfinite(*r.settle_s) ? text(*r.settle_s) + " s is out of range"
                                                       : std::string("must be a finite number")) +
                               "; allowed 0 < settle_s ≤ " + text(kMaxSettleS) + " s");
  }
  switch (r.kind) {
    case MissionKind::kTurn:
      return check_finite_within("angle_rad", r.angle_rad, kMaxTurnRad, "rad");
    case MissionKind::kMove:
      return check_finite_within("distance_m", r.distance_m, kMaxMoveM, "m");
    case MissionKind::kGoto: {
      if (r.waypoints.empty() || r.waypoints.size() > kMaxWaypoints) {
        return bad("waypoints", "a goto takes 1.." + std::to_string(kMaxWaypoints) +
                                    " waypoints, got " + std::to_string(r.waypoints.size()));
      }
      for (std::size_t i = 0; i < r.waypoints.size(); ++i) {
        const std::string at = "waypoints[" + std::to_string(i) + "].";
        if (auto e = check_finite_within(at + "x_m", r.waypoints[i].x_m, kMaxWaypointM, "m")) return e;
        if (auto e = check_finite_within(at + "y_m", r.waypoints[i].y_m, kMaxWaypointM, "m")) return e;
      }
      return std::nullopt;
    }
    case MissionKind::kNone:
    case MissionKind::kVelocity:
      break;
  }
  return bad("kind", "a mission is a turn, a move or a goto");
}

std::optional<RequestError> check_velocity(const VelocityCommand& c, const Params& params) {
  if (auto e = check_finite_within("v_mps", c.v_mps, max_velocity_mps(params), "m/s")) return e;
  return check_finite_within("yaw_radps", c.yaw_radps, max_yaw_rate_radps(params), "rad/s");
}

DriveTargets velocity_targets(const VelocityCommand& c, const Params& params) {
  checks::law::require_finite(c.v_mps, "velocity_targets", "v_mps");
  checks::law::require_finite(c.yaw_radps, "velocity_targets", "yaw_radps");
  const double r = params.geometry.wheel_radius_m;
  return {c.v_mps / r, c.yaw_radps * 0.5 * params.geometry.track_width_m / r};
}

MissionRunner::MissionRunner(const Params& params) : params_(&params), nav_(params.navigation) {
  validate(nav_);
  if (!(params.geometry.wheel_radius_m > 0.0 && params.geometry.track_width_m > 0.0)) {
    throw std::invalid_argument("MissionRunner: geometry.wheel_radius_m and track_width_m must be > 0");
  }
}

void MissionRunner::finish(MissionState state, std::string_view reason, double time_s) {
  status_.state = state;
  status_.reason = std::string(reason);
  status_.ended_s = time_s;
  if (state == MissionState::kReached) status_.progress = 1.0;
}

void MissionRunner::abort(std::string_view reason, double time_s) {
  if (!running()) return;
  finish(MissionState::kAborted, reason, time_s);
}

void MissionRunner::follow_velocity(double time_s) {
  if (running() && status_.kind == MissionKind::kVelocity) return;
  abort("replaced by a velocity command", time_s);
  const std::uint64_t id = status_.id + 1;
  status_ = MissionStatus{};
  status_.id = id;
  status_.kind = MissionKind::kVelocity;
  status_.state = MissionState::kRunning;
  status_.started_s = time_s;
}

void MissionRunner::start(const MissionRequest& request, const estimation::Pose& pose,
                          double time_s, double stood_s) {
  if (auto e = check_request(request)) throw std::invalid_argument(e->message);
  if (!(std::isfinite(stood_s) && stood_s >= 0.0)) {
    throw std::invalid_argument("MissionRunner::start: stood_s must be >= 0 s, got " + text(stood_s));
  }
  abort("replaced by a new mission", time_s);
  const std::uint64_t id = status_.id + 1;
  status_ = MissionStatus{};
  status_.id = id;
  status_.kind = request.kind;
  status_.state = MissionState::kRunning;
  status_.started_s = time_s;
  request_ = request;
  settle_s_ = request.settle_s.value_or(nav_.settle_s);
  max_settle_s_ = std::max(settle_s_, nav_.max_settle_s + (settle_s_ - nav_.settle_s));
  status_.settle_s = settle_s_;
  leg_lengths_m_.clear();
  total_length_m_ = 0.0;
  from_ = {pose.x_m, pose.y_m};
  switch (request.kind) {
    case MissionKind::kTurn:
      turn_total_rad_ = std::abs(request.angle_rad);
      begin_turn(pose.heading_rad + request.angle_rad);
      break;
    case MissionKind::kMove: {
      line_heading_rad_ = pose.heading_rad;
      direction_ = sign(request.distance_m);
      to_ = {pose.x_m + request.distance_m * std::cos(pose.heading_rad),
             pose.y_m + request.distance_m * std::sin(pose.heading_rad)};
      status_.waypoints = {to_};
      total_length_m_ = std::abs(request.distance_m);
      leg_lengths_m_ = {total_length_m_};
      begin_drive(pose);
      break;
    }
    case MissionKind::kGoto: {
      status_.waypoints = request.waypoints;
      Waypoint previous = from_;
      for (const Waypoint& w : request.waypoints) {
        leg_lengths_m_.push_back(std::hypot(w.x_m - previous.x_m, w.y_m - previous.y_m));
        total_length_m_ += leg_lengths_m_.back();
        previous = w;
      }
      status_.leg = 0;
      begin_leg(pose);
      break;
    }
    case MissionKind::kNone:
    case MissionKind::kVelocity:
      break;
  }
  best_error_s_ = time_s;
  if (stood_s < settle_s_ && (phase_ == Phase::kTurn || phase_ == Phase::kDrive)) {
    first_phase_ = phase_;
    phase_ = Phase::kStand;
    settle_started_ = true;
    settle_since_s_ = time_s;
    still_since_s_ = time_s - stood_s;
  }
}

// goto: the leg from the previous waypoint (or the start) to waypoint `leg`; turn towards it
// first when it lies off the heading. A waypoint within the tolerance is passed at once.
void MissionRunner::begin_leg(const estimation::Pose& pose) {
  while (status_.leg < request_.waypoints.size()) {
    to_ = request_.waypoints[status_.leg];
    const double dx = to_.x_m - pose.x_m;
    const double dy = to_.y_m - pose.y_m;
    if (std::hypot(dx, dy) > nav_.position_tolerance_m) break;
    from_ = to_;
    ++status_.leg;
  }
  if (status_.leg >= request_.waypoints.size()) {
    phase_ = Phase::kSettle;  // nothing left: end_leg after settling reaches the goal
    settled_from_ = Phase::kDrive;
    settle_started_ = false;
    return;
  }
  const double leg_dx = to_.x_m - from_.x_m;
  const double leg_dy = to_.y_m - from_.y_m;
  // The line's heading: along the leg, or from the rover when the leg starts where it stands.
  line_heading_rad_ = std::hypot(leg_dx, leg_dy) > nav_.position_tolerance_m
                          ? std::atan2(leg_dy, leg_dx)
                          : std::atan2(to_.y_m - pose.y_m, to_.x_m - pose.x_m);
  direction_ = 1.0;
  const double bearing = std::atan2(to_.y_m - pose.y_m, to_.x_m - pose.x_m);
  const double off = wrap(bearing - pose.heading_rad);
  if (std::abs(off) > nav_.turn_in_place_rad) {
    turn_total_rad_ = std::abs(off);
    begin_turn(pose.heading_rad + off);
  } else {
    begin_drive(pose);
  }
}

void MissionRunner::begin_turn(double target_heading_rad) {
  phase_ = Phase::kTurn;
  target_heading_rad_ = target_heading_rad;
  status_.target_heading_rad = target_heading_rad;
  turn_sign_.reset();
  best_error_ = std::numeric_limits<double>::infinity();
}

void MissionRunner::begin_drive(const estimation::Pose& pose) {
  phase_ = Phase::kDrive;
  const double ux = std::cos(line_heading_rad_);
  const double uy = std::sin(line_heading_rad_);
  const double along = ux * (to_.x_m - pose.x_m) + uy * (to_.y_m - pose.y_m);
  direction_ = sign(along);
  status_.target_heading_rad = line_heading_rad_;
  status_.remaining_rad.reset();
  best_error_ = std::numeric_limits<double>::infinity();
}

bool MissionRunner::progressed(double error, double time_s) {
  const double step = phase_ == Phase::kTurn ? kProgressStepRad : kProgressStepM;
  if (error <= best_error_ - step || !std::isfinite(best_error_)) {
    best_error_ = error;
    best_error_s_ = time_s;
  }
  return time_s - best_error_s_ <= nav_.no_progress_s;
}

DriveTargets MissionRunner::turn_targets(const estimation::Pose& pose) {
  const double e = target_heading_rad_ - pose.heading_rad;
  const double r = params_->geometry.wheel_radius_m;
  const double g = r / (0.5 * params_->geometry.track_width_m);
  const double mu = params_->operator_input.drive_rate_per_s;
  const double magnitude =
      std::max(nav_.min_spin_radps,
               std::min({nav_.max_spin_radps, nav_.heading_gain * std::abs(e),
                         std::sqrt(mu * std::abs(e) / g)}));
  return {0.0, sign(e) * magnitude};
}

DriveTargets MissionRunner::drive_targets(const estimation::Pose& pose) {
  const double r = params_->geometry.wheel_radius_m;
  const double mu = params_->operator_input.drive_rate_per_s;
  const double c = std::cos(line_heading_rad_);
  const double s = std::sin(line_heading_rad_);
  const double along = c * (to_.x_m - pose.x_m) + s * (to_.y_m - pose.y_m);
  const double left = -s * (pose.x_m - from_.x_m) + c * (pose.y_m - from_.y_m);
  const double speed_mps = std::max(
      nav_.min_speed_mps, std::min(nav_.cruise_speed_mps, std::sqrt(mu * r * std::abs(along))));
  const double reference =
      line_heading_rad_ - direction_ * std::atan(left / nav_.look_ahead_m);
  const double v2_limit = 0.5 * nav_.max_spin_radps;
  const double v2 = std::clamp(nav_.heading_gain * wrap(reference - pose.heading_rad), -v2_limit,
                               v2_limit);
  return {direction_ * speed_mps / r, v2};
}

void MissionRunner::update_progress(const estimation::Pose& pose) {
  const double c = std::cos(line_heading_rad_);
  const double s = std::sin(line_heading_rad_);
  const double along = c * (to_.x_m - pose.x_m) + s * (to_.y_m - pose.y_m);
  switch (status_.kind) {
    case MissionKind::kTurn: {
      const double e = std::abs(target_heading_rad_ - pose.heading_rad);
      status_.remaining_rad = e;
      status_.progress = turn_total_rad_ > 0.0 ? std::clamp(1.0 - e / turn_total_rad_, 0.0, 1.0) : 1.0;
      return;
    }
    case MissionKind::kMove: {
      status_.remaining_m = std::abs(along);
      status_.progress = total_length_m_ > 0.0
                             ? std::clamp(1.0 - std::abs(along) / total_length_m_, 0.0, 1.0)
                             : 1.0;
      return;
    }
    case MissionKind::kGoto: {
      double done = 0.0;
      double remaining = 0.0;
      for (std::size_t i = 0; i < leg_lengths_m_.size(); ++i) {
        if (i < status_.leg) done += leg_lengths_m_[i];
        if (i > status_.leg) remaining += leg_lengths_m_[i];
      }
      if (status_.leg < leg_lengths_m_.size()) {
        const double rest = phase_ == Phase::kTurn
                                ? std::hypot(to_.x_m - pose.x_m, to_.y_m - pose.y_m)
                                : std::max(0.0, along);
        remaining += rest;
        done += std::max(0.0, leg_lengths_m_[status_.leg] - rest);
      }
      status_.remaining_m = remaining;
      status_.remaining_rad = phase_ == Phase::kTurn
                                  ? std::optional(std::abs(target_heading_rad_ - pose.heading_rad))
                                  : std::nullopt;
      status_.progress = total_length_m_ > 0.0 ? std::clamp(done / total_length_m_, 0.0, 1.0) : 1.0;
      return;
    }
    case MissionKind::kNone:
    case MissionKind::kVelocity:
      return;
  }
}

// After settling: drive the leg again if it ended off by more than twice its tolerance, else go
// on to the next leg or end the mission.
void MissionRunner::end_leg(const estimation::Pose& pose, double time_s) {
  if (settled_from_ == Phase::kTurn) {
    const double e = target_heading_rad_ - pose.heading_rad;
    if (std::abs(e) > 2.0 * nav_.heading_tolerance_rad &&
        status_.corrections < nav_.max_corrections) {
      ++status_.corrections;
      begin_turn(target_heading_rad_);
      best_error_s_ = time_s;
      return;
    }
    if (status_.kind == MissionKind::kTurn) {
      finish(MissionState::kReached, "", time_s);
    } else {
      begin_drive(pose);
      best_error_s_ = time_s;
    }
    return;
  }
  if (status_.kind == MissionKind::kGoto && status_.leg >= request_.waypoints.size()) {
    finish(MissionState::kReached, "", time_s);
    return;
  }
  const double c = std::cos(line_heading_rad_);
  const double s = std::sin(line_heading_rad_);
  const double along = c * (to_.x_m - pose.x_m) + s * (to_.y_m - pose.y_m);
  if (std::abs(along) > 2.0 * nav_.position_tolerance_m &&
      status_.corrections < nav_.max_corrections) {
    ++status_.corrections;
    begin_drive(pose);
    best_error_s_ = time_s;
    return;
  }
  if (status_.kind == MissionKind::kMove) {
    finish(MissionState::kReached, "", time_s);
    return;
  }
  from_ = to_;
  ++status_.leg;
  if (status_.leg >= request_.waypoints.size()) {
    status_.leg = request_.waypoints.size() - 1;
    finish(MissionState::kReached, "", time_s);
    return;
  }
  begin_leg(pose);
  best_error_s_ = time_s;
}

DriveTargets MissionRunner::update(const estimation::Pose& pose, double time_s, bool stands) {
  if (!driving_mission()) return {};
  constexpr std::string_view kLaw = "MissionRunner::update";
  checks::law::require_finite(pose.x_m, kLaw, "x_m");
  checks::law::require_finite(pose.y_m, kLaw, "y_m");
  checks::law::require_finite(pose.heading_rad, kLaw, "heading_rad");
  checks::law::require_finite(pose.speed_mps, kLaw, "speed_mps");
  checks::law::require_finite(pose.yaw_rate_radps, kLaw, "yaw_rate_radps");
  update_progress(pose);
  if (phase_ == Phase::kStand) {
    if (!stood_still(pose, time_s, stands)) return {};
    phase_ = first_phase_;
    best_error_s_ = time_s;  // the no-progress time starts with the leg
  }
  if (phase_ == Phase::kTurn) {
    const double e = target_heading_rad_ - pose.heading_rad;
    if (!turn_sign_) turn_sign_ = sign(e);
    if (e == 0.0 || sign(e) != *turn_sign_) {
      // At the target, or past it: settle. Not already at the tolerance's near edge: a rover
      // stopped on soft soil turns back as the soil's shear unloads (≈ 0.01 rad on sand), and a
      // turn stopped short by the tolerance then ends more than twice the tolerance off, and so
      // does every correction stopped the same way.
      phase_ = Phase::kSettle;
      settled_from_ = Phase::kTurn;
      settle_started_ = false;
    } else {
      if (!progressed(std::abs(e), time_s)) {
        finish(MissionState::kAborted,
               "no progress for " + text(nav_.no_progress_s) + " s (" + text(std::abs(e)) +
                   " rad still to turn)",
               time_s);
        return {};
      }
      return turn_targets(pose);
    }
  }
  if (phase_ == Phase::kDrive) {
    const double c = std::cos(line_heading_rad_);
    const double s = std::sin(line_heading_rad_);
    const double along = c * (to_.x_m - pose.x_m) + s * (to_.y_m - pose.y_m);
    if (std::abs(along) <= nav_.position_tolerance_m || sign(along) != direction_) {
      phase_ = Phase::kSettle;  // there, or past it
      settled_from_ = Phase::kDrive;
      settle_started_ = false;
    } else {
      if (!progressed(std::abs(along), time_s)) {
        finish(MissionState::kAborted,
               "no progress for " + text(nav_.no_progress_s) + " s (" + text(std::abs(along)) +
                   " m still to go)",
               time_s);
        return {};
      }
      return drive_targets(pose);
    }
  }
  // Settling: zero targets until the rover has stood still for settle_s_ (or max_settle_s_).
  if (stood_still(pose, time_s, stands)) {
    end_leg(pose, time_s);
    if (running()) update_progress(pose);
  }
  return {};
}

// Zero targets meanwhile: true once the rover has stood still for settle_s_ since the standing
// began (settle_started_), or max_settle_s_ passed.
bool MissionRunner::stood_still(const estimation::Pose& pose, double time_s, bool stands) {
  const bool still = stands && std::abs(pose.yaw_rate_radps) < nav_.still_yaw_rate_radps;
  if (!settle_started_) {
    settle_started_ = true;
    settle_since_s_ = time_s;
    still_since_s_ = still ? std::optional(time_s) : std::nullopt;
  }
  if (!still) {
    still_since_s_.reset();
  } else if (!still_since_s_) {
    still_since_s_ = time_s;
  }
  return (still_since_s_ && time_s - *still_since_s_ >= settle_s_) ||
         time_s - settle_since_s_ >= max_settle_s_;
}

}  // namespace marsokhod::navigation
