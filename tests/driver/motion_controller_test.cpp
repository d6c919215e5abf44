// The motion controller's tracking (observe): l = w − ν of Definition 4.9 and the torque τ of
// (4.6) in the status, with Procedure 4.13's weight; a gait inside the slant bounds (6.4).
#include "driver/motion_controller.hpp"

#include "core/adaptation/motor_curve.hpp"
#include "core/mobility/summation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace marsokhod::driver {
namespace {

// Every motor at 0 but the joints, contracted at C = ∓1.2121 (Remark 3.1's positions).
MotorVector contracted_joints() {
  MotorVector p{};
  p[kFrontJoint] = -1.2121;
  p[kRearJoint] = 1.2121;
  return p;
}

// The front-left wheel held at d = 0.5 at U = Ū = 24 V: ŵ = ζ0·W₅₁₁(0.5) = 0.9896·1.50 = 1.4844
// rad/s, and after five cycles ν of (4.4) is ŵ (the δ of h = 0.0157 s sum to 1). A measured w
// 0.1653 rad/s above it is the load of Procedure 4.13's 5.51 N·m pushing along d (B⁺(0.5) =
// 0.030); 0.08265 below it, the same torque against d (B⁻(0.5) = 0.015).
TEST(MotionControllerTracking, StatusCarriesTheTorqueOfProcedure4_13sWeight) {
  const Params params;
  for (const auto& [defect_radps, torque_nm] : {std::pair{0.1653, 5.51}, {-0.08265, -5.51}}) {
    MotionController controller(params);
    MotorVector duty{};
    duty[kFrontLeft] = 0.5;
    for (int k = 0; k < 6; ++k) controller.record_sent(duty, 24.0);
    MotionInput input;
    input.period_s = params.cycle.period_s;
    input.shaft_velocity_radps[kFrontLeft] = 0.9896 * 1.50 + defect_radps;
    DriverStatus status;
    controller.observe(input, status);
    const MotorStatus& m = status.motors[kFrontLeft];
    EXPECT_NEAR(m.no_load_velocity_radps, 1.4844, 1e-9);
    EXPECT_NEAR(m.load_radps, defect_radps, 1e-9);
    EXPECT_NEAR(m.torque_nm, torque_nm, 1e-6);
    // A still motor at d = 0: no load, no torque.
    EXPECT_EQ(status.motors[kCenterLeft].torque_nm, 0.0);
  }
}

// Front-wheel walking on a 20° ascent (the accelerometer reads gravity pitched nose up: a1 =
// −g·sin σ < 0), the joints contracted at C = ∓1.2121 and held there (the shafts do not move).
// After 1000 cycles (λ^1000 = 4e-5 of the start left in the gravity estimate) σ = 20° and (6.4)
// gives p7_min = γ(20°) = 1.5836. The gait holds the rear joint, at C, below that bound: (4.16)
// pulls it up, and its velocity state, the command v7, has grown toward +C. Without the slant
// response the bound stays at C and the held joint is not moved.
TEST(MotionControllerGait, AJointHeldByAGaitIsPulledInsideTheSlantBound) {
  const Params params;
  for (const bool slant_response : {true, false}) {
    SCOPED_TRACE(slant_response);
    MotionController controller(params);
    const MotorVector p = contracted_joints();
    controller.reset_joint_positions(p);
    RuntimeSettings settings = runtime_settings_from(params);
    settings.switches.slant_response = slant_response;
    MotionInput input;
    input.period_s = params.cycle.period_s;
    input.shaft_position_rad = p;
    input.reference_supply_v = 24.0;
    const double sigma = 20.0 * std::numbers::pi / 180.0;
    input.accel_mps2 = {-9.81 * std::sin(sigma), 0.0, -9.81 * std::cos(sigma)};
    input.targets.gait = mobility::Gait::kFrontWheelWalking;
    input.targets.gait_speed = 1.0;
    DriverStatus status;
    for (int k = 0; k < 1000; ++k) controller.update(input, settings, status);
    EXPECT_NEAR(status.slope_rad, sigma, 0.005);
    // (C,H) was reached in the first cycle, at σ = 0; (E,H) is not, the shafts standing still.
    EXPECT_EQ(status.gait_state, 1u);
    if (slant_response) {
      EXPECT_NEAR(status.joint_bounds.rear_min_rad, 1.5836, 0.005);
      EXPECT_GT(status.commands.v7_radps, 0.5);
    } else {
      EXPECT_NEAR(status.joint_bounds.rear_min_rad, 1.2121, 1e-9);
      EXPECT_NEAR(status.commands.v7_radps, 0.0, 1e-6);
    }
  }
}

// The slope hold (slope_hold.hpp) through the controller: rolking with every wheel reading
// −5 rad/s (rolled back far behind any plan the gait makes: its wheels are asked at most
// ≈ 2.3 rad/s) for 1000 cycles, once with the hold (K = 10/s, E = 0.1 rad) and once with K = 0,
// the power management and the axle placement off so that nothing else reads the wheels. Nose up
// 20° the lost angle reaches E and each wheel is asked K·E = 1 rad/s more, forward (uphill); nose
// down, the wheels reading +5 rad/s, 1 rad/s backward. On flat ground the commands are the open
// loop's, bit for bit, whatever the wheels do.
// The status publishes the hold's share (slope_hold_radps); the plan's ν (what the stall check
// counts) is the open loop's ν either way: ν less the hold.
// One rolking run for the slope hold: every wheel reading `wheel_radps`, the slope
// `slope_deg` nose up, the supply at `supply_v` (24 V nominal), 1000 cycles.
struct HoldRun {
  MotorVector commanded{};
  MotorVector no_load{};
  MotorVector planned{};
  MotorVector hold{};
  double walking_scale = 0.0;
};

// The power management and the axle placement off, so that nothing but the hold reads the wheels.
RuntimeSettings hold_only_settings(const Params& params) {
  RuntimeSettings settings = runtime_settings_from(params);
  settings.switches.power_management = false;
  settings.switches.axle_placement = false;
  return settings;
}

// Rolking at full speed `slope_deg` nose up, every wheel reading `wheel_radps`, the joints
// contracted, at Ū = 24 V.
MotionInput rolking_up(const Params& params, double slope_deg, double wheel_radps) {
  MotionInput input;
  input.period_s = params.cycle.period_s;
  input.shaft_position_rad = contracted_joints();
  input.reference_supply_v = 24.0;
  const double sigma = slope_deg * std::numbers::pi / 180.0;
  input.accel_mps2 = {-9.81 * std::sin(sigma), 0.0, -9.81 * std::cos(sigma)};
  for (std::size_t i = 0; i < kWheelCount; ++i) input.shaft_velocity_radps[i] = wheel_radps;
  input.targets.gait = mobility::Gait::kRolking;
  input.targets.gait_speed = 1.0;
  return input;
}

HoldRun rolking_with_the_hold(double slope_deg, double wheel_radps, double gain_per_s,
                              double supply_v) {
  Params params;
  params.behaviours.slope_hold_gain_per_s = gain_per_s;
  MotionController controller(params);
  controller.reset_joint_positions(contracted_joints());
  const RuntimeSettings settings = hold_only_settings(params);
  MotionInput input = rolking_up(params, slope_deg, wheel_radps);
  input.supply_v = supply_v;
  const double sigma = slope_deg * std::numbers::pi / 180.0;
  DriverStatus status;
  for (int k = 0; k < 1000; ++k) {
    controller.record_sent(controller.update(input, settings, status), input.supply_v);
  }
  EXPECT_NEAR(status.slope_rad, sigma, 0.005);
  HoldRun out;
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    out.commanded[i] = status.motors[i].commanded_radps;
    out.hold[i] = status.motors[i].slope_hold_radps;
    out.no_load[i] = status.motors[i].no_load_velocity_radps;
  }
  out.planned = controller.planned_no_load_velocity();
  out.walking_scale = status.walking_scale;
  return out;
}

TEST(MotionControllerSlopeHold, AGaitsWheelsGetKTimesTheirLostAngleOnSlopesOnly) {
  struct Case {
    double slope_deg;
    double wheel_radps;
    double extra_radps;
  };
  for (const Case c : {Case{20.0, -5.0, 1.0}, Case{-20.0, 5.0, -1.0}, Case{0.0, -5.0, 0.0},
                       Case{0.0, 5.0, 0.0}}) {
    SCOPED_TRACE(c.slope_deg);
    SCOPED_TRACE(c.wheel_radps);
    const HoldRun held_out = rolking_with_the_hold(c.slope_deg, c.wheel_radps, 10.0, 24.0);
    const HoldRun open_out = rolking_with_the_hold(c.slope_deg, c.wheel_radps, 0.0, 24.0);
    const MotorVector& held = held_out.commanded;
    const MotorVector& open = open_out.commanded;
    for (std::size_t i = 0; i < kWheelCount; ++i) {
      if (c.extra_radps == 0.0) {
        EXPECT_EQ(held[i], open[i]) << kMotorNames[i];
      } else {
        EXPECT_NEAR(held[i] - open[i], c.extra_radps, 1e-9) << kMotorNames[i];
      }
      // K·E, up to the rounding of ŵ less the plan's ŵ
      EXPECT_NEAR(held_out.hold[i], c.extra_radps, 1e-12) << kMotorNames[i];
      EXPECT_EQ(open_out.hold[i], 0.0) << kMotorNames[i];
      EXPECT_NEAR(held_out.planned[i], open_out.planned[i], 1e-9) << kMotorNames[i];
      EXPECT_NEAR(held_out.no_load[i] - open_out.no_load[i], c.extra_radps, 1e-9)
          << kMotorNames[i];
    }
    EXPECT_EQ(held_out.hold[kFrontJoint], 0.0);
    EXPECT_EQ(held_out.hold[kRearJoint], 0.0);
    EXPECT_EQ(held[kFrontJoint], open[kFrontJoint]);
    EXPECT_EQ(held[kRearJoint], open[kRearJoint]);
  }
}

// The hold's share is what of its term the wheel's bound (5.5) lets through: nose up 20° with
// the wheels rolled back, min(ŵ_plan + K·E, ζW(1)U/Ū) − ŵ_plan for each wheel, and the plan's ν
// (what the stall check counts) is the open loop's ν whatever the share. Where the plan alone
// already asks a wheel for its bound, the share is 0 and the check counts the wheel's whole
// command (a gait pushing its wheels into a block tilts the chassis like a slope; before
// 2026-12-02 the hold's unclamped term was taken off the clamped command, the check saw the
// wheels asked nothing, and obstacle-axle-placement-off no longer latched its stall). At a low
// supply U the bounds come within K·E of the plan. (Rolking alone never puts a wheel on its
// bound: the joints bind first and scale the gait, λ = 0.04–0.16 here; the share 0 at the bound
// is the same formula, and obstacle-axle-placement-off's stall, runner_scenarios_test.cpp, is
// that case end to end.)
TEST(MotionControllerSlopeHold, TheHoldsShareIsWhatTheBoundsLetThrough) {
  const Params params;
  const adaptation::MotorCurve curve(
      adaptation::select_motor_curve(params.motor_curves, params.cycle.icr));
  std::size_t partial = 0;
  for (const double supply_v : {24.0, 2.0, 1.0, 0.5}) {
    SCOPED_TRACE(supply_v);
    const HoldRun held = rolking_with_the_hold(20.0, -5.0, 10.0, supply_v);
    const HoldRun open = rolking_with_the_hold(20.0, -5.0, 0.0, supply_v);
    const MotorVector bound = mobility::motor_velocity_bounds(params.motors.scale, 1.0, curve,
                                                              supply_v, 24.0);
    for (std::size_t i = 0; i < kWheelCount; ++i) {
      SCOPED_TRACE(kMotorNames[i]);
      const double plan = open.commanded[i];
      const double share = std::min(plan + 1.0, bound[i]) - plan;
      EXPECT_NEAR(held.hold[i], share, 1e-12);
      EXPECT_NEAR(held.commanded[i], plan + share, 1e-12);
      EXPECT_NEAR(held.planned[i], open.planned[i], 1e-9);
      if (share < 1.0) ++partial;
    }
  }
  EXPECT_GE(partial, 1u);
}

// A new stroke gives the wheels new roles, and the hold starts again from e = 0 (an anchor's
// lost angle asked of a wheel that now rolls with its axle pushes against the joint). Rolking 20°
// nose up with every wheel reading −3 rad/s (rolled back: rolking asks its wheels at most ≈ 2.3
// rad/s) and the joints following their commands exactly (w = ŵ, p integrated): while a stroke
// runs, e reaches E and every wheel gets K·E = 1 rad/s; in the cycle the gait's state changes, e
// is one cycle's h·(ν̂ − w) ≤ 0.0157·5.3 = 0.083 rad and the term K·h·(ν̂ − w) (ν̂ of the plan,
// this cycle's), below K·E.
TEST(MotionControllerSlopeHold, ANewStrokeStartsTheLostAngleAgain) {
  Params params;
  params.behaviours.slope_hold_gain_per_s = 10.0;
  MotionController controller(params);
  MotorVector p = contracted_joints();
  controller.reset_joint_positions(p);
  const RuntimeSettings settings = hold_only_settings(params);
  MotionInput input = rolking_up(params, 20.0, -3.0);
  DriverStatus status;
  const double gain = params.behaviours.slope_hold_gain_per_s;
  const double full = gain * params.behaviours.slope_hold_max_rad;
  std::size_t changes = 0;
  bool held_full = false;  // the term was K·E on every wheel in the cycle before
  for (int k = 0; k < 20000 && changes < 4; ++k) {
    input.shaft_position_rad = p;
    const std::size_t state = status.gait_state;
    const MotorVector planned = controller.planned_no_load_velocity();  // this cycle's ν̂
    const MotorVector w_hat = controller.update(input, settings, status);
    controller.record_sent(w_hat, 24.0);
    for (std::size_t j : {kFrontJoint, kRearJoint}) {
      input.shaft_velocity_radps[j] = status.motors[j].commanded_radps;
      p[j] += input.period_s * status.motors[j].commanded_radps;
    }
    if (k > 0 && status.gait_state != state) {
      SCOPED_TRACE(changes);
      EXPECT_TRUE(held_full);
      for (std::size_t i = 0; i < kWheelCount; ++i) {
        const double one_cycle = gain * input.period_s * (planned[i] + 3.0);
        EXPECT_NEAR(status.motors[i].slope_hold_radps, one_cycle, 1e-9) << kMotorNames[i];
        EXPECT_LT(status.motors[i].slope_hold_radps, full) << kMotorNames[i];
      }
      ++changes;
    }
    held_full = true;
    for (std::size_t i = 0; i < kWheelCount; ++i) {
      held_full = held_full && std::abs(status.motors[i].slope_hold_radps - full) < 1e-9;
    }
  }
  EXPECT_EQ(changes, 4u);
}

// Another gait is another role for each wheel, whatever its state's index: rolking's joints
// standing still (its stroke not reached) with every wheel rolled back 20° nose up, the hold at
// K·E; switched to worm-like, which walks in the same state, the hold starts again from one
// cycle's K·h·(ν̂ − w).
TEST(MotionControllerSlopeHold, AnotherGaitStartsTheLostAngleAgain) {
  Params params;
  MotionController controller(params);
  controller.reset_joint_positions(contracted_joints());
  const RuntimeSettings settings = hold_only_settings(params);
  MotionInput input = rolking_up(params, 20.0, -3.0);
  DriverStatus status;
  const double gain = params.behaviours.slope_hold_gain_per_s;
  const double full = gain * params.behaviours.slope_hold_max_rad;
  for (int k = 0; k < 200; ++k) {
    controller.record_sent(controller.update(input, settings, status), 24.0);
  }
  const std::size_t state = status.gait_state;
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    EXPECT_NEAR(status.motors[i].slope_hold_radps, full, 1e-9) << kMotorNames[i];
  }
  input.targets.gait = mobility::Gait::kWormLike;
  const MotorVector planned = controller.planned_no_load_velocity();
  controller.update(input, settings, status);
  EXPECT_EQ(status.gait_state, state);
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    const double one_cycle = gain * input.period_s * (planned[i] + 3.0);
    EXPECT_NEAR(status.motors[i].slope_hold_radps, one_cycle, 1e-9) << kMotorNames[i];
    EXPECT_LT(status.motors[i].slope_hold_radps, full) << kMotorNames[i];
  }
}

// An axle placement switched by 6.2.3 is another role for the wheels: worm-like 20° nose up
// (fixed ρ of 0 or 1 in each state; rolking's ε-formula gives ρ = 1 − ρ = 0.5 with the joints
// still, so no switch would show) with every wheel rolled back (−3 rad/s) and both joints held
// still under their commands (an obstacle), the axle placement on. A joint's load passes the
// threshold, its placement switches (ρ jumps to 1 − ρ: the joint is slow) within a state, and in
// that cycle the hold, at K·E the cycle before, starts again from one cycle's K·h·(ν̂ − w).
TEST(MotionControllerSlopeHold, ASwitchedAxlePlacementStartsTheLostAngleAgain) {
  Params params;
  MotionController controller(params);
  controller.reset_joint_positions(contracted_joints());
  RuntimeSettings settings = hold_only_settings(params);
  settings.switches.axle_placement = true;
  MotionInput input = rolking_up(params, 20.0, -3.0);
  input.targets.gait = mobility::Gait::kWormLike;
  DriverStatus status;
  const double gain = params.behaviours.slope_hold_gain_per_s;
  const double full = gain * params.behaviours.slope_hold_max_rad;
  bool switched = false;
  for (int k = 0; k < 2000 && !switched; ++k) {
    const std::size_t state = status.gait_state;
    const double rho_f = status.front_axle_factor, rho_r = status.rear_axle_factor;
    const double before = status.motors[kFrontLeft].slope_hold_radps;
    const MotorVector planned = controller.planned_no_load_velocity();
    controller.record_sent(controller.update(input, settings, status), 24.0);
    if (k > 0 && status.gait_state == state &&
        (status.front_axle_factor != rho_f || status.rear_axle_factor != rho_r)) {
      switched = true;
      EXPECT_NEAR(before, full, 1e-9);
      for (std::size_t i = 0; i < kWheelCount; ++i) {
        const double one_cycle = gain * input.period_s * (planned[i] + 3.0);
        EXPECT_NEAR(status.motors[i].slope_hold_radps, one_cycle, 1e-9) << kMotorNames[i];
        EXPECT_LT(status.motors[i].slope_hold_radps, full) << kMotorNames[i];
      }
    }
  }
  EXPECT_TRUE(switched);
}

// The operator's v3ᵈ (chapter 5.2) reaches the wheels as m3·v3: (4.14) ramps v3 toward the
// target (μ = 2/s: after 640 cycles, 10 s, within 1e-6 of it), and ŵ is +v3 on the left-rear and
// right-front wheels, −v3 on the left-front and right-rear ones, 0 on the centre wheels and the
// joints; nothing else is asked for, so κ = 1 and the wheels get exactly that.
// On a slope (|σ| at least the slant dead band) rolking's ε-formula stroke asks no anchor downhill
// (uphill_axle_factors): its first stroke from contracted joints moves the rear joint alone
// (measured w7 = 0.5 rad/s, extending), and the driver's ρr is 0 nose up (the rear axle stands,
// where the printed formula's ½ rolls it back downhill at half the rate the centre advances),
// 1 nose down (it goes back, uphill), ½ on flat ground or with `slope_placement` off. ρf stays ½.
TEST(MotionControllerSlopePlacement, RolkingsCentreStrokeAsksNoAnchorDownhill) {
  struct Case {
    double slope_deg;
    bool placement;
    double rear_factor;
  };
  for (const Case c : {Case{20.0, true, 0.0}, Case{-20.0, true, 1.0}, Case{0.0, true, 0.5},
                       Case{2.0, true, 0.5}, Case{20.0, false, 0.5}}) {
    SCOPED_TRACE(c.slope_deg);
    SCOPED_TRACE(c.placement);
    Params params;
    params.behaviours.slope_placement = c.placement;
    MotionController controller(params);
    controller.reset_joint_positions(contracted_joints());
    const RuntimeSettings settings = hold_only_settings(params);
    MotionInput input = rolking_up(params, c.slope_deg, 0.0);
    DriverStatus status;
    for (int k = 0; k < 1000; ++k) {  // σ settles (λ = 0.99 a cycle)
      controller.record_sent(controller.update(input, settings, status), input.supply_v);
    }
    input.shaft_velocity_radps[kRearJoint] = 0.5;
    for (int k = 0; k < 100; ++k) {  // the rear joint extends, 1.2121 → 1.99 rad
      input.shaft_position_rad[kRearJoint] += 0.5 * input.period_s;
      controller.record_sent(controller.update(input, settings, status), input.supply_v);
    }
    ASSERT_EQ(status.gait_state, 0u);
    ASSERT_NEAR(status.motors[kRearJoint].velocity_radps, 0.5, 1e-9);
    ASSERT_EQ(status.motors[kFrontJoint].velocity_radps, 0.0);
    EXPECT_NEAR(status.slope_rad, c.slope_deg * std::numbers::pi / 180.0, 0.005);
    EXPECT_EQ(status.front_axle_factor, 0.5);
    EXPECT_EQ(status.rear_axle_factor, c.rear_factor);
  }
}

TEST(MotionControllerDriving, DriftTargetDrivesTheExteriorWheelsAgainstEachOther) {
  const Params params;
  MotionController controller(params);
  const MotorVector p = contracted_joints();
  controller.reset_joint_positions(p);
  const RuntimeSettings settings = runtime_settings_from(params);
  MotionInput input;
  input.period_s = params.cycle.period_s;
  input.shaft_position_rad = p;
  input.reference_supply_v = 24.0;
  input.targets.v3_radps = -0.8;
  DriverStatus status;
  for (int k = 0; k < 640; ++k) controller.update(input, settings, status);
  const double v3 = status.commands.v3_radps;
  EXPECT_NEAR(v3, -0.8, 1e-6);
  EXPECT_EQ(status.driving_scale, 1.0);
  EXPECT_EQ(status.motors[kBackLeft].commanded_radps, v3);
  EXPECT_EQ(status.motors[kFrontRight].commanded_radps, v3);
  EXPECT_EQ(status.motors[kFrontLeft].commanded_radps, -v3);
  EXPECT_EQ(status.motors[kBackRight].commanded_radps, -v3);
  for (std::size_t motor : {kCenterLeft, kCenterRight, kFrontJoint, kRearJoint}) {
    EXPECT_EQ(status.motors[motor].commanded_radps, 0.0) << kMotorNames[motor];
  }
  EXPECT_EQ(status.commands.v1_radps, 0.0);
  EXPECT_EQ(status.commands.v4_radps, 0.0);
}

// A joint whose p̄ may be off (the encoder registers hid direction changes, motor_position.hpp)
// is pushed no further out than its bounds narrowed by as much at both ends: the rear joint at
// 1.25 rad with 0.05 rad of uncertainty stands below its narrowed p7_min = 1.2121 + 0.05, and the
// operator's v7 < 0 (down, out) is refused where it moves the joint without the uncertainty. It
// is not pulled back in (the behaviours' bounds in the status stay), and moving in is allowed.
// An uncertainty past half the range narrows both bounds to the middle: nothing moves out.
TEST(MotionControllerBounds, NoCommandPushesAJointOutPastItsUncertainty) {
  const Params params;
  const auto run = [&](double rear_uncertainty_rad, double v7_radps) {
    MotionController controller(params);
    MotorVector p{};
    p[kFrontJoint] = -1.8;
    p[kRearJoint] = 1.25;
    controller.reset_joint_positions(p);
    MotionInput input;
    input.period_s = params.cycle.period_s;
    input.shaft_position_rad = p;
    input.reference_supply_v = 24.0;
    input.position_uncertainty_rad[kRearJoint] = rear_uncertainty_rad;
    input.targets.v7_radps = v7_radps;
    DriverStatus status;
    for (int k = 0; k < 20; ++k) controller.update(input, runtime_settings_from(params), status);
    return status;
  };
  const DriverStatus certain = run(0.0, -0.3);
  EXPECT_NEAR(certain.joint_bounds.rear_min_rad, 1.2121, 1e-9);
  EXPECT_LT(certain.commands.v7_radps, -0.05);
  EXPECT_LT(run(0.03, -0.3).commands.v7_radps, 0.0);  // inside 1.2421: slowed, still out
  const DriverStatus uncertain = run(0.05, -0.3);
  EXPECT_EQ(uncertain.commands.v7_radps, 0.0);
  EXPECT_NEAR(uncertain.joint_bounds.rear_min_rad, 1.2121, 1e-9);
  EXPECT_DOUBLE_EQ(uncertain.motors[kRearJoint].position_uncertainty_rad, 0.05);
  EXPECT_EQ(run(0.05, 0.0).commands.v7_radps, 0.0);  // not pulled in
  EXPECT_GT(run(0.05, 0.3).commands.v7_radps, 0.05);  // in is fine
  EXPECT_EQ(run(5.0, -0.3).commands.v7_radps, 0.0);
  EXPECT_GT(run(5.0, 0.3).commands.v7_radps, 0.05);   // toward the middle: in
}

}  // namespace
}  // namespace marsokhod::driver
