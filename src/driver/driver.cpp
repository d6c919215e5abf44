#include "driver/driver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/mobility/lever_geometry.hpp"
#include "core/protocol/codec.hpp"
#include "driver/duty_rules.hpp"
#include "driver/lcd.hpp"

namespace marsokhod::driver {
namespace {

constexpr double kStillSpeedRadps = 0.01;  // below this every motor counts as standing
// A joint whose p̄ may be this far off (motor_position.hpp: uncertainty_counts) is reported in
// the warnings: 0.01 rad (0.6°, 183 pulses), the tolerance the soak allows a joint outside (5.3).
constexpr double kJointUncertaintyWarningRad = 0.01;

}  // namespace

const char* mode_name(DriverMode mode) {
  switch (mode) {
    case DriverMode::kStartup: return "startup";
    case DriverMode::kDriving: return "driving";
    case DriverMode::kCalibration: return "calibration";
    case DriverMode::kFault: return "fault";
  }
  return "?";
}

Driver::Driver(const Params& params, std::optional<JointMemory> kept)
    : params_(&params),
      intake_(params.cycle.icr),
      startup_(params),
      motors_(params.motors),
      sensors_(params.sensors, params.filters),
      operator_(params),
      motion_(params),
      pose_(params.geometry.wheel_radius_m),
      tip_over_({params.safety.tip_over_roll_rad, params.safety.tip_over_pitch_rad,
                 params.safety.tip_over_time_constant_s}),
      stuck_({params.safety.stuck_time_s, params.safety.stuck_min_command_radps,
              params.safety.stuck_turning_share, params.safety.stuck_min_yaw_rate_radps}),
      joint_blocked_({params.safety.joint_blocked_time_s,
                      params.safety.joint_blocked_min_command_radps,
                      params.safety.joint_blocked_turning_share}),
      missions_(params),
      // An anchor of the null's drift: a second of standing (64 readings of (3.4)).
      null_drift_(params.sensors.gyro_radps_per_count,
                  static_cast<std::size_t>(std::ceil(1.0 / params.cycle.period_s))),
      runtime_(runtime_settings_from(params)),
      kept_(std::move(kept)) {
  validate(runtime_);
  status_.settings = runtime_;
  if (kept_) startup_.continue_joints();
}

std::optional<JointMemory> Driver::joint_memory() const {
  if (kept_) return kept_;  // not judged yet: pass it on as it came
  JointMemory memory;
  if (!status_.joints_known) {
    memory.known = false;
    return memory;
  }
  if (!positions_known_) return std::nullopt;
  const tracking::MotorsSample& m = motors_.sample();
  const MotorVector p = motion_.joint_positions();
  for (std::size_t k = 0; k < 2; ++k) {
    const std::size_t j = k == 0 ? kFrontJoint : kRearJoint;
    memory.joints[k].reading = motors_.motor(j).position().last_reading();
    memory.joints[k].shaft_rad = m.position_rad[j] + position_offset_rad_[j];
    memory.joints[k].joint_rad = p[j];
    memory.joints[k].duty = duty_[j];
    memory.joints[k].uncertainty_rad = status_.motors[j].position_uncertainty_rad;
  }
  return memory;
}

void Driver::take_kept_joints() {
  if (!kept_ || !motors_.motor(kFrontJoint).started() || !motors_.motor(kRearJoint).started()) {
    return;
  }
  const tracking::MotorsSample& m = motors_.sample();
  MotorVector positions{};
  for (std::size_t i = 0; i < kMotorCount; ++i) positions[i] = m.position_rad[i] + position_offset_rad_[i];
  std::string origin = "kept across a restart (";
  std::string refused;
  // Procedure 4.3's motion after a restart may not drag a joint past its negative bound.
  std::array<double, 2> take_up_travel{Startup::kNoTravelLimit, Startup::kNoTravelLimit};
  const std::array<double, 2> negative_bound{params_->joints.front_min_rad,
                                             params_->joints.rear_min_rad};
  if (!kept_->known) refused = "the driver before the restart did not know them either";
  for (std::size_t k = 0; k < 2 && kept_->known; ++k) {
    const std::size_t j = k == 0 ? kFrontJoint : kRearJoint;
    std::string why;
    const auto restored = restore_joint(kept_->joints[k], motors_.motor(j).position().last_reading(),
                                        params_->motors.backlash_rad[j], *params_, j, why);
    if (!restored) {
      refused += (refused.empty() ? "" : "; ") + why;
      continue;
    }
    position_offset_rad_[j] = restored->shaft_rad - m.position_rad[j];
    uncertainty_origin_counts_[j] = motors_.motor(j).position().uncertainty_counts();
    uncertainty_carried_rad_[j] = kept_->joints[k].uncertainty_rad;
    positions[j] = restored->joint_rad;
    take_up_travel[k] = restored->shaft_rad - negative_bound[k];
    char text[64];
    std::snprintf(text, sizeof text, "%sµ%zu moved %+.4f rad", k == 0 ? "" : ", ", j,
                  restored->shift_rad);
    origin += text;
  }
  motion_.reset_joint_positions(positions);
  status_.joints_known = refused.empty();
  positions_known_ = refused.empty();
  joints_restored_ = refused.empty();
  status_.joint_origin = refused.empty() ? origin + " while down)" : "unknown: " + refused;
  kept_.reset();
  startup_.take_joints(take_up_travel);
}

// Procedure 4.3's motion ended where the joints stand after a restart: each shaft at the
// negative end of its gap, so p = p̄, with p̄ continued from the kept state.
void Driver::take_up_joint_gaps() {
  const tracking::MotorsSample& m = motors_.sample();
  MotorVector shaft{};
  for (std::size_t i = 0; i < kMotorCount; ++i) shaft[i] = m.position_rad[i] + position_offset_rad_[i];
  motion_.reset_joint_positions(shaft);
  // A shaft too near its negative bound to start from rest without running past it
  // (Startup::free_run_on_rad) kept its place: p = p̄, at most that far above a joint inside
  // (5.3).
  if (!startup_.take_up_skipped(0) && !startup_.take_up_skipped(1)) {
    status_.joint_origin += ", gaps taken up";
    return;
  }
  for (std::size_t k = 0; k < 2; ++k) {
    char text[96];
    const auto motor = static_cast<std::size_t>(k == 0 ? kFrontJoint : kRearJoint);
    if (startup_.take_up_skipped(k)) {
      std::snprintf(text, sizeof text, ", µ%zu's gap not taken up (%+.4f rad to its bound)",
                    motor, startup_.take_up_travel_rad(k));
    } else {
      std::snprintf(text, sizeof text, ", µ%zu's gap taken up", motor);
    }
    status_.joint_origin += text;
  }
}

// The joints' positions are unknown: nothing may move them (no gait, command or behaviour).
void Driver::hold_unknown_joints() {
  targets_.v6_radps = 0.0;
  targets_.v7_radps = 0.0;
  targets_.gait = mobility::Gait::kNone;
  targets_.front_joint_target_rad.reset();
  targets_.rear_joint_target_rad.reset();
}

void Driver::set_runtime(const RuntimeSettings& settings) {
  validate(settings);
  runtime_ = settings;
  status_.settings = settings;
}

void Driver::take_responses(const CycleResponses& r) {
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    if (r.configuration[i]) startup_.on_configured(i);
    if (r.control[i]) motors_.update_motor(*r.control[i], params_->cycle.con);
  }
  if (r.dead_man_acknowledged) startup_.on_dead_man_acknowledged();
  if (r.measurement) {
    // Standing: every motor off, and its speed averaged over the last kStillCycles cycles (125
    // ms) below the still speed. A wheel standing in soft sand rocks by a few encoder counts
    // either way (up to ±0.01 rad/s, one sample in 11–15 at or above it), which one sample would
    // take for motion; a wheel that turns on, however slowly, keeps its mean.
    recent_velocity_radps_[recent_velocities_ % kStillCycles] = motors_.sample().velocity_radps;
    ++recent_velocities_;
    const std::size_t window = std::min(recent_velocities_, kStillCycles);
    bool still = true;
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      double sum = 0.0;
      for (std::size_t k = 0; k < window; ++k) sum += recent_velocity_radps_[k][i];
      still = still && duty_[i] == 0.0 &&
              std::abs(sum / static_cast<double>(window)) < kStillSpeedRadps;
    }
    const bool all_zero = std::all_of(duty_.begin(), duty_.end(), [](double d) { return d == 0.0; });
    gyro_still_ = still;
    const double null_used = sensors_.state().gyro_null_counts;  // y^k, what (3.4) converts with
    const tracking::SensorState& s = sensors_.update(*r.measurement, still, all_zero);
    // The null's drift over a leg, from the first cycle: the start-up's standing anchors the
    // first leg; update_pose begins the leg when the odometry starts.
    const estimation::PoseCorrection c = null_drift_.update(
        status_.mission_time_s, status_.cycle_time_s > 0.0 ? status_.cycle_time_s : params_->cycle.period_s,
        r.measurement->yaw, null_used, still);
    pose_correction_.heading_rad += c.heading_rad;
    pose_correction_.x_m += c.x_m;
    pose_correction_.y_m += c.y_m;
    status_.supply_v = s.supply_v;
    status_.reference_supply_v = s.reference_supply_v;
    status_.yaw_rate_radps = s.yaw_rate_radps;
    status_.accel_mps2 = s.accel_mps2;
    status_.front_tilt_rad = s.front_tilt_rad;
    status_.rear_tilt_rad = s.rear_tilt_rad;
  }
}

void Driver::update_faults(const OperatorInput* input) {
  const auto& silent = intake_.silent_cycles();
  bool any_silent = false;
  for (std::size_t i = 0; i <= kMotorCount; ++i) {
    if (i < kMotorCount) {
      status_.motors[i].silent_cycles = silent[i];
    } else {
      status_.sensor_silent_cycles = silent[i];
    }
    if (silent[i] < params_->safety.missed_responses_limit) continue;
    any_silent = true;
    const std::string fault = "µ" + std::to_string(i) + " silent";
    if (std::find(status_.faults.begin(), status_.faults.end(), fault) == status_.faults.end()) {
      status_.faults.push_back(fault);
    }
  }
  if (input != nullptr && input->clear_faults && !any_silent) status_.faults.clear();
  status_.warnings.clear();
  if (status_.supply_v > 0.0 && status_.supply_v < params_->power.brownout_v + 0.5) {
    status_.warnings.push_back("supply " + std::to_string(status_.supply_v).substr(0, 5) +
                               " V near the brown-out voltage");
  }
  if (!status_.joints_known) {
    status_.warnings.push_back("joints held: their positions are " + status_.joint_origin +
                               "; set them vertical in calibration mode and leave it");
  }
  if (intake_.counters().malformed > 0) {
    status_.warnings.push_back("malformed frames: " + intake_.counters().last_error);
  }
  for (const std::size_t j : {kFrontJoint, kRearJoint}) {
    const double uncertainty_rad = status_.motors[j].position_uncertainty_rad;
    if (uncertainty_rad < kJointUncertaintyWarningRad) continue;
    char text[160];
    std::snprintf(text, sizeof text,
                  "µ%zu's position uncertain by %.3f rad (direction changes its registers hid); "
                  "its bounds are narrowed by as much: recalibrate (Procedure 4.3)",
                  j, uncertainty_rad);
    status_.warnings.emplace_back(text);
  }
}

MotionInput Driver::motion_input(double period_s) const {
  MotionInput in;
  in.period_s = period_s;
  const tracking::MotorsSample& m = motors_.sample();
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    in.shaft_position_rad[i] = m.position_rad[i] + position_offset_rad_[i];
    in.shaft_velocity_radps[i] = m.velocity_radps[i];
    const std::uint64_t counts = motors_.motor(i).position().uncertainty_counts();
    in.position_uncertainty_rad[i] =
        uncertainty_carried_rad_[i] +
        tracking::encoder_rad_per_count(params_->motors.encoder_pulses_per_rev) *
            static_cast<double>(counts - std::min(counts, uncertainty_origin_counts_[i]));
  }
  // Until µ8 has answered, the nominal voltage and a level rover stand in.
  in.supply_v = status_.supply_v > 1.0 ? status_.supply_v : params_->motors.nominal_supply_v;
  if (status_.supply_v > 1.0) in.reference_supply_v = status_.reference_supply_v;
  if (sensors_.state().update_count > 0) in.accel_mps2 = status_.accel_mps2;
  in.targets = targets_;
  in.stopping = stopping_;
  return in;
}

// p⁰ := p̄⁰ of Remark 3.1, less how far each shaft dragged its joint toward the negative end
// after they met (`dragged_rad`: front, rear; Startup::over_travel_rad), but inside (5.3). The
// rear joint's drag is outward, below p7_min: it is taken at its bound, where (4.16) rests.
// Outside, (4.16) pulls it in, for a few mrad with a duty too small to move it (0.014), and a
// joint motor held at a duty keeps the rover from standing still: the gyro's null (3.4) is then
// not learnt, and a square's heading drifted by 4.7 rad (odometry-square-hard, seed 18).
void Driver::reset_joint_positions(std::array<double, 2> dragged_rad) {
  const tracking::MotorsSample& m = motors_.sample();
  MotorVector shaft{};
  for (std::size_t i = 0; i < kMotorCount; ++i) shaft[i] = m.position_rad[i] + position_offset_rad_[i];
  const std::array<std::size_t, 2> joints{kFrontJoint, kRearJoint};
  const std::array<mobility::JointBounds, 2> bounds{mobility::front_joint_bounds(params_->joints),
                                                    mobility::rear_joint_bounds(params_->joints)};
  for (std::size_t k = 0; k < 2; ++k) {
    const std::size_t j = joints[k];
    shaft[j] = bounds[k].clamp(params_->motors.initial_position_rad[j] - dragged_rad[k]);
    position_offset_rad_[j] = shaft[j] - m.position_rad[j];
    uncertainty_origin_counts_[j] = motors_.motor(j).position().uncertainty_counts();
    uncertainty_carried_rad_[j] = 0.0;
  }
  motion_.reset_joint_positions(shaft);
  status_.joints_known = true;
  positions_known_ = true;
}

MotorVector Driver::wanted_duties(double time_s, const MotionInput& input) {
  MotorVector wanted{};
  if (status_.mode == DriverMode::kDriving) {
    wanted = motion_.update(input, runtime_, status_);
    if (!status_.joints_known) wanted[kFrontJoint] = wanted[kRearJoint] = 0.0;
    return wanted;
  }
  motion_.observe(input, status_);
  if (status_.mode == DriverMode::kStartup && startup_.phase() == StartupPhase::kCalibrate) {
    const auto d = startup_.calibrate(
        time_s, {input.shaft_position_rad[kFrontJoint], input.shaft_position_rad[kRearJoint]},
        {input.shaft_velocity_radps[kFrontJoint], input.shaft_velocity_radps[kRearJoint]},
        {status_.motors[kFrontJoint].no_load_velocity_radps,
         status_.motors[kRearJoint].no_load_velocity_radps},
        on_slope());
    wanted[kFrontJoint] = d[0];
    wanted[kRearJoint] = d[1];
  } else if (status_.mode == DriverMode::kCalibration) {
    const auto d = mobility::calibration_duties(targets_.joint_buttons, params_->operator_input);
    wanted[kFrontJoint] = d[0];
    wanted[kRearJoint] = d[1];
  }
  return wanted;
}

const std::vector<protocol::CanFrame>& Driver::step(double time_s,
                                                    std::span<const protocol::CanFrame> received,
                                                    const OperatorInput* input) {
  if (!start_time_s_) {
    start_time_s_ = time_s;
    last_time_s_ = time_s;
  }
  const double period_s = time_s > last_time_s_ ? time_s - last_time_s_ : params_->cycle.period_s;
  status_.cycle_time_s = time_s - last_time_s_;
  status_.mission_time_s = time_s - *start_time_s_;
  last_time_s_ = time_s;
  ++status_.cycle;

  take_responses(intake_.take(received, expected_));
  take_kept_joints();
  status_.bus = intake_.counters();
  if (input != nullptr) {
    const auto rejection = operator_.receive(*input, time_s);
    if (rejection) status_.operator_rejection = *rejection;
  }
  targets_ = operator_.targets(time_s);
  if (!status_.joints_known) hold_unknown_joints();
  stopping_ = operator_.stopping(time_s);
  status_.operator_timeout = operator_.timed_out(time_s);
  status_.stop_latched = operator_.stop_latched();
  status_.stop_reason = operator_.stop_reason();
  update_mission(time_s);
  status_.targets = {targets_.v1_radps, targets_.v2_radps, targets_.v3_radps, targets_.v4_radps,
                     targets_.v6_radps, targets_.v7_radps};
  update_faults(input);
  update_failsafes(period_s);

  status_.startup_phase = startup_.phase();
  if (!status_.faults.empty()) {
    status_.mode = DriverMode::kFault;
  } else if (startup_.phase() != StartupPhase::kDone) {
    status_.mode = DriverMode::kStartup;
  } else {
    status_.mode = targets_.calibration_mode ? DriverMode::kCalibration : DriverMode::kDriving;
  }
  const MotionInput in = motion_input(period_s);
  const MotorVector wanted = wanted_duties(time_s, in);
  if (startup_.phase() == StartupPhase::kDone && !startup_calibrated_) {
    startup_calibrated_ = true;
    if (joints_restored_) {
      take_up_joint_gaps();
    } else if (!startup_.continues_joints()) {
      reset_joint_positions(startup_.over_travel_rad());  // Procedure 4.3
      status_.joint_origin = "Procedure 4.3";
    }
  }
  const bool calibrating = status_.mode == DriverMode::kCalibration;
  if (was_calibrating_ && !calibrating && status_.mode == DriverMode::kDriving) {
    reset_joint_positions();  // the operator left calibration mode
    status_.joint_origin = "calibration mode (Procedure 4.3)";
  }
  was_calibrating_ = calibrating;

  for (std::size_t i = 0; i < kMotorCount; ++i) {
    // What is sent is pwm/icr: the status and (4.4) see the quantised duty.
    const double duty = next_duty(duty_[i], wanted[i], params_->safety);
    duty_[i] = sent_duty(duty, params_->cycle.icr);
    status_.motors[i].duty = duty_[i];
  }
  status_.supply_current_bound_a = motion_.supply_current_bound_a(duty_, in);
  motion_.record_sent(duty_, in.supply_v);
  update_pose(period_s);
  status_.startup_phase = startup_.phase();
  encode_requests();
  return requests_;
}

// A mission needs the driving mode, the operator's input in time and no stop; any non-neutral
// input of the operator takes over. It drives through v1 and v2 (m1, m2) like the operator.
void Driver::update_mission(double time_s) {
  const auto why_not = [&]() -> std::optional<std::string> {
    if (!status_.faults.empty()) return "fault: " + status_.faults.front();
    if (operator_.timed_out(time_s)) {
      return "the operator fell silent for " +
             number_text(params_->safety.operator_timeout_s) + " s";
    }
    if (operator_.stop_latched()) return "stopped: " + operator_.stop_reason();
    if (status_.mode == DriverMode::kStartup) return std::string("the driver is starting up");
    if (status_.mode == DriverMode::kCalibration) return std::string("calibration mode");
    return std::nullopt;
  };
  if (auto request = operator_.take_mission()) {
    missions_.start(*request, status_.pose, time_s,  // checked by the operator channel
                    null_drift_.standing_s());
  } else if (operator_.velocity_in_force(time_s)) {
    if (auto reason = why_not()) {
      missions_.abort(*reason, time_s);  // starts again when the velocity is heeded again
    } else {
      missions_.follow_velocity(time_s);
    }
  } else if (missions_.running() && missions_.status().kind == navigation::MissionKind::kVelocity) {
    missions_.abort(why_not().value_or("the operator's input is no longer a velocity"), time_s);
  }
  if (missions_.driving_mission()) {
    if (auto reason = why_not()) {
      missions_.abort(*reason, time_s);
    } else if (!is_neutral(targets_)) {
      missions_.abort("the operator took over", time_s);
    } else {
      const navigation::DriveTargets t = missions_.update(status_.pose, time_s, gyro_still_);
      targets_.v1_radps = t.v1_radps;
      targets_.v2_radps = t.v2_radps;
    }
  }
  status_.mission = missions_.status();
}

// Dead reckoning (pose_estimator.hpp) from the centre wheels once their controllers answer.
// The odometry frame starts where start-up ends: Procedure 4.3 swings the joints with the rover
// standing, and until then the gyro has not seen the rover still long enough to learn its null
// (3.4) — a unit's null 5 counts off the TYP line turns the heading by 0.04 rad in 2 s.
void Driver::update_pose(double period_s) {
  if (startup_.phase() != StartupPhase::kDone) return;
  if (!motors_.motor(kCenterLeft).started() || !motors_.motor(kCenterRight).started()) return;
  if (!pose_started_) {
    pose_started_ = true;
    null_drift_.begin_leg();      // the leg starts at the odometry's origin
    pose_correction_ = {};  // what the start-up's motion gained belongs to no pose
  }
  const MotorStatus& left = status_.motors[kCenterLeft];
  const MotorStatus& right = status_.motors[kCenterRight];
  estimation::OdometryInput in;
  in.period_s = period_s;
  // Standing with every bridge off the rover cannot turn: the gyro's reading is its null and
  // quantisation noise, which (3.4) learns from; integrated, it would turn the heading by
  // 0.0170·(m − y) rad/s — the stand's mean reading m less the null y learnt before — and no
  // anchor takes that back (null_drift.hpp corrects the moving cycles). The 2 m square stands
  // 8–10 s a leg: its worst heading error on seeds 1–20 fell from 0.0529 to 0.034 rad with this.
  in.yaw_rate_radps = gyro_still_ ? 0.0 : status_.yaw_rate_radps;
  in.slope_rad = status_.slope_rad;
  in.pitch_rad = status_.attitude.pitch_rad;
  in.left_angle_rad = left.shaft_position_rad;
  in.right_angle_rad = right.shaft_position_rad;
  in.left_load_radps = left.load_radps;
  in.right_load_radps = right.load_radps;
  in.left_no_load_radps = left.no_load_velocity_radps;
  in.right_no_load_radps = right.no_load_velocity_radps;
  const estimation::Pose& p = pose_.update(in);
  // The step just taken, along its midpoint heading, for the position's share of the drift.
  null_drift_.add_motion(p.speed_mps * period_s, p.heading_rad - 0.5 * p.yaw_rate_radps * period_s);
  if (pose_correction_ != estimation::PoseCorrection{}) {
    pose_.correct(pose_correction_.heading_rad, pose_correction_.x_m, pose_correction_.y_m);
    pose_correction_ = {};
  }
  status_.pose = pose_.pose();
}

// The failsafes that need an estimate: each latches a fault (and so stops the motors) as a silent
// controller does. The tip-over fault comes back after a clear while the rover is still tilted;
// the stall's time starts again after one.
void Driver::update_failsafes(double period_s) {
  const auto latch = [this](const std::string& fault, std::string_view kind) {
    const bool latched = std::any_of(status_.faults.begin(), status_.faults.end(),
                                     [&](const std::string& f) { return f.starts_with(kind); });
    if (!latched) status_.faults.push_back(fault);
  };
  const tracking::SensorState& s = sensors_.state();
  if (s.update_count > attitude_readings_) {
    attitude_readings_ = s.update_count;
    if (const auto fault = tip_over_.update(status_.accel_mps2, period_s)) latch(*fault, "tip-over");
    status_.attitude = tip_over_.attitude();
  }
  // ν of (4.4) and the measured w of two motors, for a stall check.
  const auto pair = [this](std::size_t a, std::size_t b, std::array<double, 2>& no_load,
                           std::array<double, 2>& velocity) {
    no_load = {status_.motors[a].no_load_velocity_radps, status_.motors[b].no_load_velocity_radps};
    velocity = {motors_.sample().velocity_radps[a], motors_.sample().velocity_radps[b]};
  };
  estimation::StuckInput in;
  in.period_s = period_s;
  pair(kCenterLeft, kCenterRight, in.no_load_radps, in.velocity_radps);
  // The centre wheels' ν without the slope hold's term: the hold pulls a gait's anchor back to
  // where the plan left it, and an anchor held still is not a stalled drive (slope_hold.hpp).
  const MotorVector planned = motion_.planned_no_load_velocity();
  in.no_load_radps = {planned[kCenterLeft], planned[kCenterRight]};
  in.yaw_rate_radps = status_.yaw_rate_radps;
  in.driving = status_.mode == DriverMode::kDriving;  // the mode of the cycle before
  in.motion_asked = targets_.v1_radps != 0.0 || targets_.v2_radps != 0.0 ||
                    (targets_.gait != mobility::Gait::kNone && targets_.gait_speed != 0.0);
  if (const auto fault = stuck_.update(in)) latch(*fault, "stuck");
  status_.stalled_s = stuck_.stalled_s();
  estimation::JointBlockedInput joints;
  joints.period_s = period_s;
  pair(kFrontJoint, kRearJoint, joints.no_load_radps, joints.velocity_radps);
  joints.driving = in.driving;
  for (const std::string& fault : joint_blocked_.update(joints)) {
    latch(fault, fault.starts_with("front") ? "front joint blocked" : "rear joint blocked");
  }
  status_.joint_stalled_s = joint_blocked_.stalled_s();
}

bool Driver::on_slope() const {
  if (sensors_.state().update_count == 0) return false;
  const auto& a = status_.accel_mps2;
  const double g = std::hypot(a[0], a[1], a[2]);
  if (!(g > 0.1 * params_->sensors.gravity_mps2)) return false;
  // The angle between the measured gravity and the chassis' down axis (−x3).
  const double tilt_rad = std::acos(std::clamp(-a[2] / g, -1.0, 1.0));
  return tilt_rad > params_->behaviours.slant_deadband_rad;
}

std::string Driver::lcd_text() const { return lcd_characters(status_); }

void Driver::encode_requests() {
  requests_.clear();
  const int icr = params_->cycle.icr;
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    const auto node = static_cast<std::uint8_t>(i);
    if (!startup_.configured(i)) {
      requests_.push_back(protocol::encode(protocol::ConfigurationRequest{
          node, static_cast<std::uint16_t>(icr), 0, static_cast<std::uint8_t>(params_->cycle.con)}));
    } else {
      requests_.push_back(protocol::encode(control_request(node, duty_[i], icr)));
    }
  }
  if (startup_.phase() == StartupPhase::kEnableDeadMan) {
    requests_.push_back(protocol::encode(
        protocol::DeadManRequest{static_cast<std::uint8_t>(params_->safety.dead_man_dog)}));
  }
  protocol::MeasurementRequest m;
  status_.lcd = lcd_text();
  std::copy_n(status_.lcd.begin(), 8, m.lcd.begin());
  m.led0 = status_.mode == DriverMode::kDriving && !status_.operator_timeout;
  m.led1 = status_.mode == DriverMode::kFault;
  requests_.push_back(protocol::encode(m));
  expected_.fill(true);
}

}  // namespace marsokhod::driver
