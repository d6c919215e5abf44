#include "runner/soak_checker.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

namespace marsokhod::runner {
namespace {

using protocol::kDeadManTickUs;

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[160];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

std::string motor(std::size_t i) { return "µ" + std::to_string(i); }

// Every number of the status, by name, for the NaN/Inf check.
void for_each_number(const driver::DriverStatus& s,
                     const std::function<void(const char*, double)>& visit) {
  visit("mission_time_s", s.mission_time_s);
  visit("cycle_time_s", s.cycle_time_s);
  visit("supply_v", s.supply_v);
  visit("reference_supply_v", s.reference_supply_v);
  visit("yaw_rate_radps", s.yaw_rate_radps);
  for (double a : s.accel_mps2) visit("accel_mps2", a);
  visit("front_tilt_rad", s.front_tilt_rad);
  visit("rear_tilt_rad", s.rear_tilt_rad);
  visit("slope_rad", s.slope_rad);
  for (const driver::MotorStatus& m : s.motors) {
    for (double v : {m.shaft_position_rad, m.position_rad, m.position_uncertainty_rad,
                     m.velocity_radps, m.no_load_velocity_radps, m.load_radps,
                     m.commanded_radps, m.slope_hold_radps, m.duty}) {
      visit("motors[]", v);
    }
  }
  visit("max_duty", s.max_duty);
  visit("driving_scale", s.driving_scale);
  visit("walking_scale", s.walking_scale);
  for (const driver::TargetStatus* t : {&s.targets, &s.commands}) {
    for (double v : {t->v1_radps, t->v2_radps, t->v3_radps, t->v4_radps, t->v6_radps, t->v7_radps}) {
      visit("targets/commands", v);
    }
  }
  visit("gait_speed", s.gait_speed);
  visit("front_axle_factor", s.front_axle_factor);
  visit("rear_axle_factor", s.rear_axle_factor);
  const driver::JointBoundsStatus& b = s.joint_bounds;
  for (double v : {b.front_min_rad, b.front_max_rad, b.rear_min_rad, b.rear_max_rad}) {
    visit("joint_bounds", v);
  }
}

}  // namespace

const char* invariant_name(Invariant invariant) {
  switch (invariant) {
    case Invariant::kFinite: return "finite";
    case Invariant::kDutyBound: return "duty-bound";
    case Invariant::kDutyStep: return "duty-step";
    case Invariant::kJointBounds: return "joint-bounds";
    case Invariant::kMissedCounted: return "missed-counted";
    case Invariant::kSilentReported: return "silent-reported";
    case Invariant::kFaultStop: return "fault-stop";
    case Invariant::kOperatorStop: return "operator-stop";
    case Invariant::kDeadMan: return "dead-man";
    case Invariant::kRestart: return "restart";
    case Invariant::kSupplyWarning: return "supply-warning";
  }
  return "?";
}

InvariantChecker::InvariantChecker(const Params& params, CheckerLimits limits)
    : params_(&params),
      limits_(limits),
      cycle_us_(std::llround(params.cycle.period_s * 1e6)),
      stop_allowance_us_(std::llround(
          (params.safety.operator_timeout_s +
           std::max(std::log(2.0) / params.operator_input.drive_rate_per_s,
                    std::log(2.0) / params.joints.control_rate_per_s) +
           (std::ceil(1.0 / params.safety.max_duty_step) + 3.0) * params.cycle.period_s) *
          1e6)) {
  context_.icr.fill(static_cast<std::uint16_t>(params.cycle.icr));
}

void InvariantChecker::add(Report& out, Invariant invariant, const CycleView& c,
                           std::string detail) {
  out.push_back({invariant, c.time_us, std::move(detail)});
}

std::array<InvariantChecker::SentDuty, kMotorCount> InvariantChecker::sent_duties(
    const CycleView& c) const {
  std::array<SentDuty, kMotorCount> out{};  // no request, or a configuration request: pwm 0
  for (const protocol::CanFrame& frame : c.sent) {
    const protocol::DecodeResult r = protocol::decode(frame, context_);
    if (!r.ok()) continue;
    if (const auto* q = std::get_if<protocol::ControlRequest>(&r.message())) {
      if (q->node < kMotorCount) out[q->node] = {q->drv ? -q->pwm : q->pwm, q->drv};
    }
  }
  return out;
}

std::array<bool, kMotorCount + 1> InvariantChecker::answered(const CycleView& c) const {
  std::array<bool, kMotorCount + 1> out{};
  for (const protocol::CanFrame& frame : c.received) {
    const protocol::DecodeResult r = protocol::decode(frame, context_);
    if (!r.ok()) continue;
    std::visit(
        [&out](const auto& m) {
          using T = std::decay_t<decltype(m)>;
          if constexpr (std::is_same_v<T, protocol::ControlResponse> ||
                        std::is_same_v<T, protocol::ConfigurationResponse>) {
            if (m.node < kMotorCount) out[m.node] = true;
          } else if constexpr (std::is_same_v<T, protocol::MeasurementResponse> ||
                               std::is_same_v<T, protocol::DeadManResponse>) {
            out[kMotorCount] = true;
          }
        },
        r.message());
  }
  return out;
}

std::vector<Violation> InvariantChecker::check(const CycleView& c) {
  Report out;
  if (c.operator_command) last_command_us_ = c.time_us;
  if (!c.driver_running || c.status == nullptr) {
    check_driver_down(c, out);
    check_joints_down(c, out);
    previous_ = {};  // a driver that comes back configures µ0–µ7 with pwm = 0 first
    previous_running_ = false;
    return out;
  }
  const bool restarted = !previous_running_;
  if (restarted) {
    if (ever_ran_) check_restart(c, out);
    missing_ = {};
    missed_total_ = 0;
    // encoder_faulted_ stays: a restarted driver continues from the kept joint state, and
    // with it from the pulses its predecessor lost.
    low_supply_cycles_ = 0;
  }
  const auto duties = sent_duties(c);
  check_finite(c, out);
  check_responses(c, out);
  check_duties(c, duties, out);
  check_joints(c, out);
  check_operator_stop(c, duties, out);
  check_supply(c, reported_supply_v(c), out);
  previous_ = duties;
  previous_running_ = true;
  ever_ran_ = true;
  last_running_us_ = c.time_us;
  stop_frames_lost_then_ = c.stop_frames_lost;
  return out;
}

void InvariantChecker::check_finite(const CycleView& c, Report& out) {
  ++evaluations_;
  std::string bad;
  for_each_number(*c.status, [&bad](const char* name, double v) {
    if (!std::isfinite(v) && bad.empty()) bad = std::string(name) + " = " + std::to_string(v);
  });
  if (!bad.empty()) add(out, Invariant::kFinite, c, "status " + bad);
}

void InvariantChecker::check_duties(const CycleView& c,
                                    const std::array<SentDuty, kMotorCount>& duties,
                                    Report& out) {
  const int icr = params_->cycle.icr;
  const SafetyParams& safety = params_->safety;
  const double half_count = 0.5 / icr;
  const int step_counts = static_cast<int>(std::lround(safety.max_duty_step * icr));
  const double bound = c.status->max_duty;
  const bool fault = c.status->mode == driver::DriverMode::kFault;
  evaluations_ += fault ? 3 : 2;
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    const double d = static_cast<double>(duties[i].signed_pwm) / icr;
    const double before = static_cast<double>(previous_[i].signed_pwm) / icr;
    const double allowed = std::max(bound, std::abs(before) - safety.max_duty_step);
    if (std::abs(d) > limits_.duty_ceiling || std::abs(d) > allowed + half_count) {
      add(out, Invariant::kDutyBound, c,
          motor(i) + format(" |d| = %.4f above D = %.4f (previous %.4f)", std::abs(d), bound, before) +
              format(", ceiling %.4f", limits_.duty_ceiling));
    }
    if (std::abs(duties[i].signed_pwm - previous_[i].signed_pwm) > step_counts) {
      add(out, Invariant::kDutyStep, c,
          motor(i) + format(" d went from %.4f to %.4f, more than the step %.4f", before, d,
                            safety.max_duty_step));
    }
    if (duties[i].drv != previous_[i].drv &&
        std::abs(d) > safety.direction_change_duty + half_count) {
      add(out, Invariant::kDutyStep, c,
          motor(i) + format(" drv toggled at |d| = %.4f > %.4f", std::abs(d),
                            safety.direction_change_duty));
    }
    if (fault && std::abs(d) > std::max(0.0, std::abs(before) - safety.max_duty_step) + half_count) {
      add(out, Invariant::kFaultStop, c,
          motor(i) + format(" |d| = %.4f in fault mode, previous %.4f: not stopping", std::abs(d),
                            before));
    }
  }
}

namespace {

// (5.3) of the front and the rear joint.
std::array<std::pair<double, double>, 2> joint_bounds(const JointParams& j) {
  return {{{j.front_min_rad, j.front_max_rad}, {j.rear_min_rad, j.rear_max_rad}}};
}

double excess_over(const std::pair<double, double>& bounds, double p) {
  return std::max(bounds.first - p, p - bounds.second);
}

std::string joint_bounds_detail(std::size_t k, double p, double excess,
                                const std::pair<double, double>& bounds) {
  return std::string(k == 0 ? "front" : "rear") +
         format(" joint %.4f rad is %.4f rad outside (5.3) [%.4f, ", p, excess, bounds.first) +
         format("%.4f]", bounds.second);
}

}  // namespace

void InvariantChecker::check_joints(const CycleView& c, Report& out) {
  ++evaluations_;
  const auto bounds = joint_bounds(params_->joints);
  const std::array<std::size_t, 2> motors{kFrontJoint, kRearJoint};
  const bool starting = c.status->mode == driver::DriverMode::kStartup;
  for (std::size_t k = 0; k < 2; ++k) {
    encoder_faulted_[k] = encoder_faulted_[k] || c.joint_encoder_fault[k];
    // A joint whose encoder lost pulses: only the driver's own estimate can be held to (5.3).
    const bool unknown = encoder_faulted_[k];
    const double truth = c.joint_angle_rad[k];
    if (unknown) {
      max_unknown_joint_excess_rad_ =
          std::max(max_unknown_joint_excess_rad_, excess_over(bounds[k], truth));
    }
    // Until Procedure 4.3 has set p⁰ the driver has no estimate to hold (its p is the raw shaft).
    if (unknown && starting) continue;
    const double p = unknown ? c.status->motors[motors[k]].position_rad : truth;
    const double excess = excess_over(bounds[k], p);
    const bool worst = excess > max_joint_excess_rad_;
    if (!worst && !(excess > limits_.joint_tolerance_rad)) continue;
    const std::string detail = joint_bounds_detail(k, p, excess, bounds[k]) +
                               (unknown ? " (the driver's estimate: its encoder lost pulses)" : "");
    if (worst) note_joint_excess(c, excess, detail);
    if (excess > limits_.joint_tolerance_rad) add(out, Invariant::kJointBounds, c, detail);
  }
}

void InvariantChecker::check_joints_down(const CycleView& c, Report& out) {
  ++evaluations_;
  const auto bounds = joint_bounds(params_->joints);
  for (std::size_t k = 0; k < 2; ++k) {
    encoder_faulted_[k] = encoder_faulted_[k] || c.joint_encoder_fault[k];
    const double truth = c.joint_angle_rad[k];
    const double excess = excess_over(bounds[k], truth);
    if (encoder_faulted_[k]) {
      // The driver steered by a wrong p before it went down: not the run-on's doing.
      max_unknown_joint_excess_rad_ = std::max(max_unknown_joint_excess_rad_, excess);
      continue;
    }
    max_down_joint_excess_rad_ = std::max(max_down_joint_excess_rad_, excess);
    const bool worst = excess > max_joint_excess_rad_;
    if (!worst && !(excess > limits_.joint_tolerance_rad)) continue;
    const std::string detail =
        joint_bounds_detail(k, truth, excess, bounds[k]) + " while the driver is down";
    if (worst) note_joint_excess(c, excess, detail);
    if (excess > limits_.joint_tolerance_rad) add(out, Invariant::kJointBounds, c, detail);
  }
}

void InvariantChecker::note_joint_excess(const CycleView& c, double excess, std::string detail) {
  max_joint_excess_rad_ = excess;
  max_joint_excess_at_ = Violation{Invariant::kJointBounds, c.time_us, std::move(detail)};
}

void InvariantChecker::check_responses(const CycleView& c, Report& out) {
  evaluations_ += 2;
  const auto got = answered(c);
  const bool expected = previous_running_;  // the driver sent every controller a request then
  for (std::size_t i = 0; i <= kMotorCount; ++i) {
    if (!expected || got[i]) {
      missing_[i] = 0;
      continue;
    }
    ++missing_[i];
    ++missed_total_;
    const std::string fault = motor(i) + " silent";
    const auto& faults = c.status->faults;
    if (missing_[i] >= params_->safety.missed_responses_limit &&
        std::find(faults.begin(), faults.end(), fault) == faults.end()) {
      add(out, Invariant::kSilentReported, c,
          fault + " for " + std::to_string(missing_[i]) + " cycles and not reported");
    }
  }
  if (c.status->bus.missed != missed_total_) {
    add(out, Invariant::kMissedCounted, c,
        "status counts " + std::to_string(c.status->bus.missed) + " missed responses, the bus " +
            std::to_string(missed_total_));
  }
}

void InvariantChecker::check_operator_stop(const CycleView& c,
                                           const std::array<SentDuty, kMotorCount>& duties,
                                           Report& out) {
  if (c.status->mode == driver::DriverMode::kStartup) return;
  ++evaluations_;
  if (last_command_us_ && c.time_us < *last_command_us_ + stop_allowance_us_) return;
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    if (duties[i].signed_pwm == 0) continue;
    const double silent_s =
        last_command_us_ ? static_cast<double>(c.time_us - *last_command_us_) * 1e-6 : -1.0;
    add(out, Invariant::kOperatorStop, c,
        motor(i) + format(" d = %.4f with the operator silent for %.4f s", 
                          static_cast<double>(duties[i].signed_pwm) / params_->cycle.icr,
                          silent_s) +
            (last_command_us_ ? "" : " (no command yet)"));
    return;  // one report a cycle
  }
}

void InvariantChecker::check_driver_down(const CycleView& c, Report& out) {
  if (!last_running_us_) return;
  ++evaluations_;
  const std::int64_t deadline_us =
      *last_running_us_ + kDeadManTickUs * params_->safety.dead_man_dog + cycle_us_;
  if (c.time_us < deadline_us) return;
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    if (c.motor_duty[i] == 0.0) continue;
    // µ8 sends again one tick later for each stop frame to µi that the bus lost.
    const std::uint64_t lost = c.stop_frames_lost[i] - stop_frames_lost_then_[i];
    if (c.time_us < deadline_us + kDeadManTickUs * static_cast<std::int64_t>(lost)) continue;
    add(out, Invariant::kDeadMan, c,
        motor(i) + format(" still at d = %.4f %.3f s after the driver's last request",
                          c.motor_duty[i],
                          static_cast<double>(c.time_us - *last_running_us_) * 1e-6) +
            (lost > 0 ? " (" + std::to_string(lost) + " of µ8's stop frames to it lost)" : ""));
    return;
  }
}

void InvariantChecker::check_restart(const CycleView& c, Report& out) {
  ++evaluations_;
  const driver::DriverStatus& s = *c.status;
  if (s.mode != driver::DriverMode::kStartup || s.cycle != 1) {
    add(out, Invariant::kRestart, c,
        std::string("a restarted driver in mode ") + driver::mode_name(s.mode) + " at cycle " +
            std::to_string(s.cycle));
  }
  for (const protocol::CanFrame& frame : c.sent) {
    const protocol::DecodeResult r = protocol::decode(frame, context_);
    if (r.ok() && std::holds_alternative<protocol::ControlRequest>(r.message())) {
      add(out, Invariant::kRestart, c, "a restarted driver sent a control request first");
      return;
    }
  }
}

std::optional<double> InvariantChecker::reported_supply_v(const CycleView& c) const {
  std::optional<double> supply_v;
  for (const protocol::CanFrame& frame : c.received) {
    const protocol::DecodeResult r = protocol::decode(frame, context_);
    if (!r.ok()) continue;
    if (const auto* m = std::get_if<protocol::MeasurementResponse>(&r.message())) {
      supply_v = params_->sensors.supply(m->vcc);  // the latest one counts, as in the driver
    }
  }
  return supply_v;
}

void InvariantChecker::check_supply(const CycleView& c, std::optional<double> reported_v,
                                    Report& out) {
  // Without a reading this cycle the driver keeps its last one, and so does the count.
  if (reported_v) {
    const bool low = *reported_v < params_->power.brownout_v + 0.5;
    low_supply_cycles_ = low ? low_supply_cycles_ + 1 : 0;
  }
  if (low_supply_cycles_ < limits_.supply_cycles) return;
  ++evaluations_;
  const auto& w = c.status->warnings;
  const bool warned = std::any_of(w.begin(), w.end(), [](const std::string& text) {
    return text.rfind("supply ", 0) == 0;
  });
  if (!warned) {
    add(out, Invariant::kSupplyWarning, c,
        format("µ8 reported %.3f V (true %.3f V) for %.0f readings and no warning",
               reported_v.value_or(std::nan("")), c.supply_v, low_supply_cycles_));
  }
}

}  // namespace marsokhod::runner
