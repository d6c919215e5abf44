#include "driver/motion_controller.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/adaptation/backlash.hpp"
#include "core/adaptation/load_torque.hpp"
#include "core/adaptation/no_load_velocity.hpp"
#include "core/adaptation/voltage_drop.hpp"
#include "core/behaviour/contract_on_turn.hpp"
#include "core/behaviour/load_distribution.hpp"
#include "core/behaviour/power_management.hpp"
#include "core/behaviour/slant_response.hpp"
#include "core/behaviour/supply_current.hpp"
#include "core/control/bounded_velocity_control.hpp"
#include "core/control/position_control.hpp"
#include "core/control/velocity_control.hpp"
#include "core/mobility/elementary_motion.hpp"
#include "core/mobility/joint_compensation.hpp"
#include "core/mobility/lever_geometry.hpp"
#include "core/mobility/summation.hpp"
#include "core/protocol/messages.hpp"
#include "core/tracking/clock.hpp"
#include "driver/duty_rules.hpp"
#include "driver/joint_margin.hpp"

namespace marsokhod::driver {
namespace {

constexpr double kInsideBound = 0.999;  // targets strictly inside ±C keep (4.15)'s log defined
// Commands this small are at rest: under one pwm count (W(1/511) ≈ 0.004 rad/s by the W₅₁₁
// table) and inside the motors' dead zone, so cutting them to 0 moves nothing.
constexpr double kRestRadps = 1e-3;

double max_abs_wheel(const MotorVector& v) {
  double m = 0.0;
  for (std::size_t i = 0; i < kWheelCount; ++i) m = std::max(m, std::abs(v[i]));
  return m;
}

// The joint command may not push a joint further out of its bounds (5.3)/(6.4); back in is fine.
double respect_bounds(double command, double position, double min_rad, double max_rad) {
  if (position <= min_rad && command < 0.0) return 0.0;
  if (position >= max_rad && command > 0.0) return 0.0;
  return command;
}

// (4.4) as the driver applies it. The thesis' w^k is µi's answer to the request of cycle k (µi
// samples vel when the request arrives, and the ReadyBoard waited for the answer within the
// cycle); the driver receives that answer one cycle later, with the frames of cycle k + 1. So the
// w the driver has in cycle k is the thesis' w^(k−1), and the ν to compare it with is the
// thesis' ν^(k−1) = Σ_j δ^j ŵ^(k−1−j): the table's δ shifted by one cycle (δ⁰ of the driver is
// 0 whatever the table says). The calibration of Procedure 4.8 writes δ in the thesis' indexing.
adaptation::NoLoadEstimator driver_estimator(const Params& params) {
  ResponseParams response =
      adaptation::select_response(params.responses, params.cycle.period_s, params.cycle.con);
  response.delta.insert(response.delta.begin(), 0.0);
  return adaptation::NoLoadEstimator(response);
}


}  // namespace

struct MotionController::JointCommands {
  double front_radps = 0.0;  // v6
  double rear_radps = 0.0;   // v7
  mobility::AxleFactors factors;
};

MotionController::MotionController(const Params& params)
    : params_(&params),
      curve_(adaptation::select_motor_curve(params.motor_curves, params.cycle.icr)),
      load_gains_(&adaptation::select_load_gains(params.load_gains, params.cycle.icr)),
      backlash_(params.motors),
      estimator_(driver_estimator(params)),
      plan_estimator_(driver_estimator(params)),
      joints_(joint_bounds_with_backlash_margin(params.joints, params.motors)),
      joint_dead_time_s_(joint_dead_time_s(params)),
      run_on_s_(params.safety.dead_man_dog > 0
                    ? protocol::kDeadManTickUs * 1e-6 * params.safety.dead_man_dog +
                          joint_dead_time_s_
                    : 0.0),
      gait_(params.geometry, joints_, params.gaits, params.motors),
      slope_(params.sensors.gravity_mps2) {}

void MotionController::reset_joint_positions(const MotorVector& position_rad) {
  backlash_.reset(position_rad);
  joint_velocity_ = {};
  estimator_ = driver_estimator(*params_);
  plan_estimator_ = driver_estimator(*params_);
  slope_hold_.reset();
  hold_radps_ = {};
  hold_role_ = {};
}

void MotionController::observe(const MotionInput& input, DriverStatus& status) {
  joint_velocity_ = {};  // not driving: the joints' command starts again from rest
  slope_hold_.reset();
  hold_radps_ = {};
  hold_role_ = {};
  track(input, status);
}

void MotionController::track(const MotionInput& input, DriverStatus& status) {
  backlash_.update(input.shaft_position_rad, input.shaft_velocity_radps);
  const MotorVector w = backlash_.joint_velocity_radps();
  const MotorVector p = backlash_.joint_position_rad();
  velocity_ = w;
  // (4.4) one cycle late (driver_estimator): the history of the commands sent is all it needs.
  const MotorVector nu = estimator_.no_load_velocity_radps();
  load_ = adaptation::load(w, nu);
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    MotorStatus& m = status.motors[i];
    m.shaft_position_rad = input.shaft_position_rad[i];
    m.position_rad = p[i];
    m.position_uncertainty_rad = input.position_uncertainty_rad[i];
    m.velocity_radps = w[i];
    m.no_load_velocity_radps = nu[i];
    m.load_radps = load_[i];
    // (4.6) at the duty the motor ran at while w was measured (sent the cycle before).
    m.torque_nm = adaptation::torque_estimate_nm(load_[i], last_duty_[i], *load_gains_);
  }
}

MotorVector MotionController::ramp_driving(const MotionInput& input,
                                           const RuntimeSettings& settings,
                                           DriverStatus& status) {
  const double w_max = params_->motors.max_no_load_speed_radps;
  const control::ControlParams drive{params_->operator_input.drive_rate_per_s, w_max,
                                     input.period_s};
  const std::array<double, 4> wanted{input.targets.v1_radps, input.targets.v2_radps,
                                     input.targets.v3_radps, input.targets.v4_radps};
  for (std::size_t j = 0; j < wanted.size(); ++j) {
    const double target =
        std::clamp(wanted[j] * settings.speed_scale, -kInsideBound * w_max, kInsideBound * w_max);
    const double c = control::velocity_control(drive_velocity_[j], target, drive);
    drive_velocity_[j] = control::step({0.0, drive_velocity_[j]}, c, drive).velocity;
  }
  status.commands.v1_radps = drive_velocity_[0];
  status.commands.v2_radps = drive_velocity_[1];
  status.commands.v3_radps = drive_velocity_[2];
  status.commands.v4_radps = drive_velocity_[3];
  const double p6 = status.motors[kFrontJoint].position_rad;
  const double p7 = status.motors[kRearJoint].position_rad;
  const mobility::Lever front = mobility::front_lever(p6, params_->geometry);
  const mobility::Lever rear = mobility::rear_lever(p7, params_->geometry);
  return mobility::driving_motion({drive_velocity_[0], drive_velocity_[1], drive_velocity_[2],
                                   drive_velocity_[3]},
                                  front.clearance_m, rear.clearance_m, params_->spin);
}

MotionController::JointCommands MotionController::joint_commands(const MotionInput& input,
                                                                 const RuntimeSettings& settings,
                                                                 DriverStatus& status) {
  const control::MotionState front{predicted_joint_position(kFrontJoint, status), joint_velocity_[0]};
  const control::MotionState rear{predicted_joint_position(kRearJoint, status), joint_velocity_[1]};
  // The gait runs inside the behaviours' bounds of this cycle (6.4) (chapter 6.2's summation):
  // its targets are clipped to them and (4.16) pulls a joint back inside.
  const JointBoundsStatus& b = status.joint_bounds;
  // On a slope (|σ| at least the slant dead band, as for the slope hold) the ε-formula's strokes
  // ask no anchor downhill (axle_placement.hpp).
  const double uphill = params_->behaviours.slope_placement
                            ? behaviour::uphill_side(status.slope_rad, params_->behaviours)
                            : 0.0;
  const mobility::GaitOutput gait = gait_.update(
      {input.targets.gait, input.targets.gait_speed, intent_, front, rear, input.period_s,
       status.motors[kFrontJoint].velocity_radps, status.motors[kRearJoint].velocity_radps,
       mobility::JointBounds{b.front_min_rad, b.front_max_rad},
       mobility::JointBounds{b.rear_min_rad, b.rear_max_rad}, uphill});
  status.gait = input.targets.gait;
  status.gait_state = gait.state_index;
  status.gait_speed = input.targets.gait_speed;
  JointCommands out;
  gait_running_ = gait.active;
  if (gait.active) {
    out.front_radps = gait.front_command_radps;
    out.rear_radps = gait.rear_command_radps;
    out.factors = gait.factors;
    return out;
  }
  const control::ControlParams joint = control::joint_control_params(*params_);
  const double limit = kInsideBound * joint.max_speed;
  // 6.2.2: contract while spinning; v̄ = w/max|n| keeps the wheels' share feasible.
  const double w_max = params_->motors.max_no_load_speed_radps;
  const double n6 = max_abs_wheel(mobility::front_joint_compensation(
      front.position, status.front_axle_factor, params_->geometry));
  const double n7 = max_abs_wheel(mobility::rear_joint_compensation(
      rear.position, status.rear_axle_factor, params_->geometry));
  const behaviour::JointVelocityTargets targets = behaviour::contract_joints_when_turning(
      {std::clamp(input.targets.v6_radps, -limit, limit),
       std::clamp(input.targets.v7_radps, -limit, limit)},
      input.targets.v2_radps * settings.speed_scale, w_max, std::max(n6, 1e-9),
      std::max(n7, 1e-9), settings.switches);
  // A position target (Procedure 4.17) is reached with (4.15), inside the bounds (6.4).
  const auto& p6d = input.targets.front_joint_target_rad;
  const auto& p7d = input.targets.rear_joint_target_rad;
  const double c6 =
      p6d ? control::position_velocity_control(
                front, {std::clamp(*p6d, b.front_min_rad, b.front_max_rad), 0.0}, joint)
          : control::bounded_velocity_control(front, std::clamp(targets.front_radps, -limit, limit),
                                              b.front_min_rad, b.front_max_rad, joint);
  const double c7 =
      p7d ? control::position_velocity_control(
                rear, {std::clamp(*p7d, b.rear_min_rad, b.rear_max_rad), 0.0}, joint)
          : control::bounded_velocity_control(rear, std::clamp(targets.rear_radps, -limit, limit),
                                              b.rear_min_rad, b.rear_max_rad, joint);
  out.front_radps = control::step(front, c6, joint).velocity;
  out.rear_radps = control::step(rear, c7, joint).velocity;
  out.factors.front = mobility::front_axle_factor(
      intent_, mobility::front_clearance_intent(front.velocity));
  out.factors.rear =
      mobility::rear_axle_factor(intent_, mobility::rear_clearance_intent(rear.velocity));
  return out;
}

MotionController::JointCommands MotionController::stopping_joint_commands() {
  const control::ControlParams joint = control::joint_control_params(*params_);
  JointCommands out;
  std::array<double, 2> v{};
  for (std::size_t j = 0; j < 2; ++j) {
    const control::MotionState state{0.0, joint_velocity_[j]};
    v[j] = control::step(state, control::velocity_control(state.velocity, 0.0, joint), joint).velocity;
  }
  out.front_radps = v[0];
  out.rear_radps = v[1];
  out.factors.front = mobility::front_axle_factor(intent_, mobility::front_clearance_intent(v[0]));
  out.factors.rear = mobility::rear_axle_factor(intent_, mobility::rear_clearance_intent(v[1]));
  return out;
}

double MotionController::predicted_joint_position(std::size_t motor,
                                                  const DriverStatus& status) const {
  const double v = joint_velocity_[motor == kFrontJoint ? 0 : 1];
  return status.motors[motor].position_rad + v * joint_dead_time_s_;
}

bool MotionController::at_rest() const {
  const auto small = [](double v) { return std::abs(v) < kRestRadps; };
  return std::all_of(drive_velocity_.begin(), drive_velocity_.end(), small) &&
         std::all_of(joint_velocity_.begin(), joint_velocity_.end(), small);
}

behaviour::JointBounds MotionController::with_backlash_margin(behaviour::JointBounds bounds,
                                                             const DriverStatus& status) const {
  const auto margin = [&](std::size_t motor) {
    return positive_bound_margin_rad(params_->joints.backlash_uncertainty,
                                     params_->motors.backlash_rad[motor],
                                     status.motors[motor].shaft_position_rad,
                                     status.motors[motor].position_rad);
  };
  bounds.front_max_rad = std::max(bounds.front_min_rad, bounds.front_max_rad - margin(kFrontJoint));
  bounds.rear_max_rad = std::max(bounds.rear_min_rad, bounds.rear_max_rad - margin(kRearJoint));
  return bounds;
}

behaviour::JointBounds MotionController::narrowed_by_uncertainty(behaviour::JointBounds bounds,
                                                                const DriverStatus& status) {
  // What the encoder registers hid (motor_position.hpp): the joint may lie that far from p̄
  // either way, so both bounds move in by as much (to the middle at most).
  const auto narrow = [](double& min_rad, double& max_rad, double uncertainty_rad) {
    const double in_rad = std::min(uncertainty_rad, 0.5 * (max_rad - min_rad));
    min_rad += in_rad;
    max_rad -= in_rad;
  };
  narrow(bounds.front_min_rad, bounds.front_max_rad,
         status.motors[kFrontJoint].position_uncertainty_rad);
  narrow(bounds.rear_min_rad, bounds.rear_max_rad,
         status.motors[kRearJoint].position_uncertainty_rad);
  return bounds;
}

MotorVector MotionController::to_duty(const MotorVector& w_hat, const MotionInput& input) const {
  MotorVector duty{};
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    duty[i] = adaptation::duty_for_no_load_velocity(curve_, w_hat[i], params_->motors.scale[i],
                                                    input.supply_v,
                                                    params_->motors.nominal_supply_v);
  }
  return duty;
}

void MotionController::update_duty_bound(const MotionInput& input,
                                         const RuntimeSettings& settings, DriverStatus& status) {
  // (6.3): D from the last duty cycles sent and the loads they met, and the measured drop
  // beyond what (4.5) makes of them.
  PowerParams power = params_->power;
  power.max_drop_v = settings.max_drop_v;
  if (input.reference_supply_v > 1.0 && input.period_s > 0.0) {
    drop_excess_.update(input.reference_supply_v - input.supply_v,
                        adaptation::voltage_drop_v(last_duty_, load_, power), input.period_s);
  }
  status.max_duty = behaviour::next_duty_bound(last_duty_, load_, power, settings.switches,
                                               drop_excess_.excess_v());
}

behaviour::JointBounds MotionController::update_slope_and_bounds(const MotionInput& input,
                                                                 const RuntimeSettings& settings,
                                                                 DriverStatus& status) {
  // 6.2.1: gravity, slope σ and the joint bounds (6.4).
  // The lever correction is filtered with the readings (slope_estimate.hpp).
  const auto& a = input.accel_mps2;
  if (std::hypot(a[0], a[1], a[2]) > 0.1 * params_->sensors.gravity_mps2) {
    const double p6 = status.motors[kFrontJoint].position_rad;
    const double p7 = status.motors[kRearJoint].position_rad;
    slope_.update(a, mobility::front_lever(p6, params_->geometry).inclination_rad,
                  mobility::rear_lever(p7, params_->geometry).inclination_rad,
                  params_->filters.gravity_lambda);
  }
  status.slope_rad = slope_.slope_rad();
  // Slopes within the dead band count as flat: noise and bumps must not move the joints. Beyond
  // it γ(σ) applies unchanged; (4.16) smooths the step of the bound at the threshold.
  const double slope = behaviour::slope_beyond_dead_band(status.slope_rad, params_->behaviours);
  const behaviour::JointBounds bounds =
      with_backlash_margin(behaviour::slant_joint_bounds(slope, params_->joints,
                                                         params_->geometry, settings.switches),
                           status);
  status.joint_bounds = {bounds.front_min_rad, bounds.front_max_rad, bounds.rear_min_rad,
                         bounds.rear_max_rad};
  return bounds;
}

MotorVector MotionController::walking_motion(JointCommands joints,
                                             const behaviour::JointBounds& bounds,
                                             const MotionInput& input,
                                             const RuntimeSettings& settings,
                                             DriverStatus& status) {
  const double h = input.period_s;
  // 6.2.3's axles: how much slower than driven each axle's wheels turn, once both stopped.
  const auto axle = [&](std::size_t left, std::size_t right) {
    return behaviour::axle_resistance_radps(
        load_[left], status.motors[left].no_load_velocity_radps, load_[right],
        status.motors[right].no_load_velocity_radps, params_->behaviours);
  };
  const double front_axle = axle(kFrontLeft, kFrontRight);
  const double centre_axle = axle(kCenterLeft, kCenterRight);
  const double rear_axle = axle(kBackLeft, kBackRight);
  const auto front_place = behaviour::next_axle_placement(
      front_placement_, joints.factors.front, load_[kFrontJoint],
      status.motors[kFrontJoint].velocity_radps, {front_axle, centre_axle}, h,
      params_->behaviours, settings.switches);
  const auto rear_place = behaviour::next_axle_placement(
      rear_placement_, joints.factors.rear, load_[kRearJoint],
      status.motors[kRearJoint].velocity_radps, {rear_axle, centre_axle}, h,
      params_->behaviours, settings.switches);
  front_placement_ = front_place.state;
  rear_placement_ = rear_place.state;
  status.front_axle_factor = front_place.placement;
  status.rear_axle_factor = rear_place.placement;
  // No command pushes a joint further out than the bounds less its position's uncertainty; one
  // found inside that band is not pulled back in (it would hold a duty to move a few pulses,
  // and the rover would never stand still for the gyro's null).
  const behaviour::JointBounds outward = narrowed_by_uncertainty(bounds, status);
  joints.front_radps = respect_bounds(joints.front_radps, predicted_joint_position(kFrontJoint, status),
                                      outward.front_min_rad, outward.front_max_rad);
  joints.rear_radps = respect_bounds(joints.rear_radps, predicted_joint_position(kRearJoint, status),
                                     outward.rear_min_rad, outward.rear_max_rad);
  // Should the computer die after this cycle, the joints run on for µ8's delay: keep that run
  // inside (5.3) less the backlash margin (joint_margin.hpp) and the uncertainty, whatever the
  // behaviours' bounds.
  const behaviour::JointBounds hard = narrowed_by_uncertainty(
      with_backlash_margin({params_->joints.front_min_rad, params_->joints.front_max_rad,
                            params_->joints.rear_min_rad, params_->joints.rear_max_rad},
                           status),
      status);
  const auto shaft_load = [&](std::size_t motor) {
    return input.shaft_velocity_radps[motor] - status.motors[motor].no_load_velocity_radps;
  };
  joints.front_radps = run_on_limited_radps(
      joints.front_radps, predicted_joint_position(kFrontJoint, status), hard.front_min_rad,
      hard.front_max_rad, run_on_s_, shaft_load(kFrontJoint));
  joints.rear_radps = run_on_limited_radps(
      joints.rear_radps, predicted_joint_position(kRearJoint, status), hard.rear_min_rad,
      hard.rear_max_rad, run_on_s_, shaft_load(kRearJoint));
  joint_velocity_ = {joints.front_radps, joints.rear_radps};
  status.commands.v6_radps = joints.front_radps;
  status.commands.v7_radps = joints.rear_radps;
  // n6·w6, n7·w7 with w from (4.2) on the velocity assigned to the joint motor (chapter 4.4's
  // ŵ6(t), ŵ7(t)) rather than on the measured one: the wheels turn with the joint from the first
  // cycle it is driven, so a joint that must pull the rover along is not held by still wheels
  // (with the measured w the wheels only follow a joint that already moves); P± of (4.2) keeps
  // them still while the shaft crosses its gap, as chapter 4.1 demands (docs/decisions.md).
  const auto assigned_joint_velocity = [&](std::size_t motor, double command_radps) {
    return adaptation::backlash_velocity(status.motors[motor].shaft_position_rad, command_radps,
                                         status.motors[motor].position_rad,
                                         params_->motors.backlash_rad[motor]);
  };
  return mobility::walking_motion(
      {status.motors[kFrontJoint].position_rad, status.motors[kRearJoint].position_rad,
       joints.front_radps, joints.rear_radps,
       assigned_joint_velocity(kFrontJoint, joints.front_radps),
       assigned_joint_velocity(kRearJoint, joints.rear_radps), front_place.placement,
       rear_place.placement},
      params_->geometry);
}

MotorVector MotionController::update(const MotionInput& input, const RuntimeSettings& settings,
                                     DriverStatus& status) {
  track(input, status);
  update_duty_bound(input, settings, status);
  const behaviour::JointBounds bounds = update_slope_and_bounds(input, settings, status);
  // Remark 5.5, then the motions of (5.4).
  intent_ = mobility::driving_intent(intent_, input.targets.v1_radps);
  const MotorVector driving = ramp_driving(input, settings, status);
  gait_running_ = false;  // joint_commands says whether a gait runs
  const JointCommands joints =
      input.stopping ? stopping_joint_commands() : joint_commands(input, settings, status);
  const MotorVector walking = walking_motion(joints, bounds, input, settings, status);
  // The slope hold on the angle the gait's wheels lost downhill against the plan (its ν̂ from
  // the commands less the hold's own term).
  // A new stroke (the gait or its state) or an axle placement switched by 6.2.3 gives the wheels
  // new roles: an anchor's lost angle asked of a wheel that now rolls with its axle pushes against
  // the joint (tried: the joint-blocked fault in obstacle-axle-placement-on and
  // worm-like-slope-slant-on). The hold starts again from e = 0 at each change. Not at every
  // change of ρ: the ε-formula's ρ moves every cycle with the joints' velocities, but only picks
  // a representative of the same motion (axle_placement.hpp).
  {
    const HoldRole role{status.gait, status.gait_state, front_placement_.switched,
                        rear_placement_.switched};
    if (role != hold_role_) slope_hold_.reset();
    hold_role_ = role;
  }
  const MotorVector hold = slope_hold_.update(velocity_, plan_estimator_.no_load_velocity_radps(),
                                              status.slope_rad, gait_running_ && !input.stopping,
                                              input.period_s, params_->behaviours);
  const bool at_rest_stopping = input.stopping && at_rest();
  const MotorVector h_load =
      input.stopping ? MotorVector{}
                     : behaviour::load_distribution_radps(load_, drive_velocity_[0],
                                                          params_->load_distribution,
                                                          settings.switches);
  // (5.4)–(5.6) under D, then the load distribution h (6.5)/(6.6) within the same bounds.
  // planned: the same without the slope hold's term, within the same bounds.
  struct Plan {
    mobility::Summation sum;
    MotorVector w_hat{};
    MotorVector planned{};
  };
  const auto plan = [&](double max_duty) {
    const MotorVector limit = mobility::motor_velocity_bounds(
        params_->motors.scale, max_duty, curve_, input.supply_v, params_->motors.nominal_supply_v);
    Plan p{mobility::sum_motions(driving, walking, limit), {}, {}};
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      const double planned = p.sum.velocities_radps[i] + h_load[i];
      p.w_hat[i] = std::clamp(planned + hold[i], -limit[i], limit[i]);
      p.planned[i] = std::clamp(planned, -limit[i], limit[i]);
    }
    return p;
  };
  status.current_duty_bound = 1.0;
  if (settings.supply == SupplyKind::kTether && !at_rest_stopping) {
    // Field Experiment 1.1: the largest D whose duties, after the slew rule, would draw no more
    // than the tether's limit even if every motor stalled (supply_current.hpp).
    const auto current_at = [&](double max_duty) {
      const MotorVector wanted = to_duty(plan(max_duty).w_hat, input);
      MotorVector sent{};
      for (std::size_t i = 0; i < kMotorCount; ++i) {
        // As Driver sends it: the slew rule, then pwm/icr.
        const double duty = next_duty(last_duty_[i], wanted[i], params_->safety);
        sent[i] = sent_duty(duty, params_->cycle.icr);
      }
      return supply_current_bound_a(sent, input);
    };
    // From the last cycle's D_I: two evaluations of the bound instead of twelve while D_I stays
    // within a resolution step (supply_current.hpp).
    status.current_duty_bound = behaviour::current_duty_bound_from(
        last_current_duty_bound_, std::min(behaviour::kMinimumDutyBound, status.max_duty),
        status.max_duty, params_->power.current.tether_current_limit_a, current_at);
    last_current_duty_bound_ = status.current_duty_bound;
    status.max_duty = std::min(status.max_duty, status.current_duty_bound);
  }
  const Plan p = plan(status.max_duty);
  status.driving_scale = p.sum.driving_scale;
  status.walking_scale = p.sum.walking_scale;
  if (at_rest_stopping) {
    drive_velocity_ = {};
    joint_velocity_ = {};
    for (MotorStatus& m : status.motors) m.commanded_radps = m.slope_hold_radps = 0.0;
    status.commands = {};
    slope_hold_.reset();
    hold_radps_ = {};
    return MotorVector{};
  }
  // The hold's share is what of its term the bounds let through: where the plan alone already
  // asks for a motor's bound, none (the stall check then counts the motor's whole command).
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    hold_radps_[i] = p.w_hat[i] - p.planned[i];
    status.motors[i].commanded_radps = p.w_hat[i];
    status.motors[i].slope_hold_radps = hold_radps_[i];
  }
  return to_duty(p.w_hat, input);
}

double MotionController::supply_current_bound_a(const MotorVector& duty,
                                                const MotionInput& input) const {
  const SupplyCurrentParams& current = params_->power.current;
  // The higher of U and Ū: a stall torque grows with the voltage the supply recovers to. And
  // µ8's reading may lie below the supply by the conversion's error: the bound is worked out at
  // the highest supply the reading admits.
  const double supply_v =
      std::max(input.supply_v, input.reference_supply_v) + current.supply_reading_error_v;
  double total_a = current.base_current_a;
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    total_a += behaviour::motor_current_bound_a(duty[i], input.shaft_velocity_radps[i], supply_v,
                                                current);
  }
  return total_a;
}

void MotionController::record_sent(const MotorVector& duty, double supply_v) {
  MotorVector w_hat{};
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    w_hat[i] = adaptation::no_load_velocity(curve_, duty[i], params_->motors.scale[i], supply_v,
                                            params_->motors.nominal_supply_v);
  }
  estimator_.push(w_hat);
  MotorVector planned{};
  for (std::size_t i = 0; i < kMotorCount; ++i) planned[i] = w_hat[i] - hold_radps_[i];
  plan_estimator_.push(planned);
  last_duty_ = duty;
}

}  // namespace marsokhod::driver
