// The joints stay inside (5.3) on every unit: a rear joint driven at full speed into each of its
// bounds by the driver's MotionController, against a plant that differs from the model the way
// drawn units do — its backlash gap 15 % narrower or wider than the configured 14°, its motor
// 10 % faster or slower than ζW(d)U/Ū, with a first-order lag, and its shaft position reaching
// the driver one cycle late (µi samples it when the request arrives).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/adaptation/motor_curve.hpp"
#include "core/adaptation/no_load_estimator.hpp"
#include "core/adaptation/no_load_velocity.hpp"
#include "driver/duty_rules.hpp"
#include "driver/joint_margin.hpp"
#include "driver/motion_controller.hpp"
#include "driver/startup.hpp"

namespace marsokhod::driver {
namespace {

struct Unit {
  double gap_share = 1.0;    // b_t / b
  double speed_share = 1.0;  // the motor's speed over the model's
  double lag_s = 0.012;
};

// Drives the rear joint at v7 for `seconds` from p7 (the shaft on the gap's negative end, as after
// Procedure 4.3); returns the true joint's lowest and highest positions. With `die_after` ≥ 0
// the computer dies after that cycle's request: the motor keeps its duty until µ8's dead man's
// switch sets pwm = 0, 0.262144·dog s later, and then stops with its lag.
std::pair<double, double> drive_rear_joint(const Unit& unit, double start_rad, double v7_radps,
                                           double seconds, int die_after = -1,
                                           const Params& params = Params{}) {
  const double h = params.cycle.period_s;
  const double b = params.motors.backlash_rad[kRearJoint] * unit.gap_share;
  const adaptation::MotorCurve curve(
      adaptation::select_motor_curve(params.motor_curves, params.cycle.icr));
  MotionController motion(params);
  MotorVector shaft{};
  shaft[kFrontJoint] = params.motors.initial_position_rad[kFrontJoint];
  shaft[kRearJoint] = start_rad;
  motion.reset_joint_positions(shaft);
  double joint = start_rad;
  double speed = 0.0;
  double duty = 0.0;
  MotorVector measured = shaft;  // one cycle late
  MotorVector measured_speed{};
  double lowest = joint;
  double highest = joint;
  RuntimeSettings settings = runtime_settings_from(params);
  settings.switches.slant_response = false;
  // One cycle of the driver: its request, the duty step rule, the shaft one cycle late.
  const auto drive_cycle = [&] {
    MotionInput in;
    in.period_s = h;
    in.shaft_position_rad = measured;
    in.shaft_velocity_radps = measured_speed;
    in.supply_v = params.motors.nominal_supply_v;
    in.targets.v7_radps = v7_radps;
    DriverStatus status;
    const MotorVector wanted = motion.update(in, settings, status);
    duty = next_duty(duty, wanted[kRearJoint], params.safety);
    MotorVector sent{};
    sent[kRearJoint] = duty;
    motion.record_sent(sent, in.supply_v);
    measured[kRearJoint] = shaft[kRearJoint];
    measured_speed[kRearJoint] = speed;
  };
  const double dead_man_s = 0.262144 * params.safety.dead_man_dog;
  for (int k = 0; k < static_cast<int>(seconds / h); ++k) {
    if (die_after < 0 || k <= die_after) {
      drive_cycle();
    } else if ((k - die_after) * h >= dead_man_s) {
      duty = 0.0;  // µ8 has stopped the motor
    }
    const double target =
        unit.speed_share * adaptation::no_load_velocity(curve, duty,
                                                        params.motors.scale[kRearJoint],
                                                        params.motors.nominal_supply_v,
                                                        params.motors.nominal_supply_v);
    for (int step = 0; step < 16; ++step) {
      const double dt = h / 16.0;
      speed += (target - speed) * dt / unit.lag_s;
      shaft[kRearJoint] += speed * dt;
      joint = std::clamp(joint, shaft[kRearJoint] - b, shaft[kRearJoint]);
      lowest = std::min(lowest, joint);
      highest = std::max(highest, joint);
    }
  }
  return {lowest, highest};
}

class JointBoundsOnEveryUnit : public ::testing::TestWithParam<Unit> {};

TEST_P(JointBoundsOnEveryUnit, AFullSpeedExtensionStopsInsideTheUpperBound) {
  const Params params;
  const auto [lowest, highest] = drive_rear_joint(GetParam(), params.joints.rear_min_rad, 1.4, 12.0);
  EXPECT_LE(highest, params.joints.rear_max_rad + 0.01);
  // It got there: within the full margin and the tolerance of the bound.
  EXPECT_GE(highest, params.joints.rear_max_rad - 0.0375 - 0.05);
  EXPECT_GE(lowest, params.joints.rear_min_rad - 0.01);
}

TEST_P(JointBoundsOnEveryUnit, AFullSpeedContractionStopsInsideTheLowerBound) {
  const Params params;
  const auto [lowest, highest] = drive_rear_joint(GetParam(), 2.2, -1.4, 12.0);
  EXPECT_GE(lowest, params.joints.rear_min_rad - 0.01);
  EXPECT_LE(lowest, params.joints.rear_min_rad + 0.05);
  EXPECT_LE(highest, params.joints.rear_max_rad + 0.01);
}

// The computer dies at any cycle of a full-speed approach to either bound: the joint runs on
// for µ8's delay at its last duty and still stops inside (5.3) by the tolerance, with the
// shipped dog = 1 (0.26 s) and with dog = 4 (1.05 s). Without the run-on limit a joint at
// C = 0.7 rad/s would run 0.18 rad on (0.73 rad with dog = 4).
TEST_P(JointBoundsOnEveryUnit, AJointThatRunsOnAfterTheComputerDiesStopsInsideTheBounds) {
  for (const int dog : {1, 4}) {
    Params params;
    params.safety.dead_man_dog = dog;
    const double run_on_s = 0.262144 * dog;
    const int cycles = static_cast<int>(5.0 / params.cycle.period_s);
    const int after = static_cast<int>((run_on_s + 1.0) / params.cycle.period_s);
    for (int die = 0; die < cycles; die += 4) {
      const double seconds = (die + after) * params.cycle.period_s;
      const auto up =
          drive_rear_joint(GetParam(), params.joints.rear_min_rad, 1.4, seconds, die, params);
      ASSERT_LE(up.second, params.joints.rear_max_rad + 0.01)
          << "extending, dog " << dog << ", died after cycle " << die;
      const auto down = drive_rear_joint(GetParam(), 2.2, -1.4, seconds, die, params);
      ASSERT_GE(down.first, params.joints.rear_min_rad - 0.01)
          << "contracting, dog " << dog << ", died after cycle " << die;
    }
  }
}

TEST(RunOnLimit, ACommandTowardABoundStopsThereWithinTheRunOnTime) {
  // p = 2.0 of [1.2121, 2.55], T_run = 0.5 s: up at most 0.55/0.5 = 1.1 rad/s, down 1.5758.
  EXPECT_DOUBLE_EQ(run_on_limited_radps(2.0, 2.0, 1.2121, 2.55, 0.5), 0.55 / 0.5);
  EXPECT_DOUBLE_EQ(run_on_limited_radps(0.3, 2.0, 1.2121, 2.55, 0.5), 0.3);  // below the limit
  EXPECT_DOUBLE_EQ(run_on_limited_radps(-2.0, 2.0, 1.2121, 2.55, 0.5), -(2.0 - 1.2121) / 0.5);
  // Past a bound: nothing further out, back in freely.
  EXPECT_EQ(run_on_limited_radps(0.2, 2.6, 1.2121, 2.55, 0.5), 0.0);
  EXPECT_EQ(run_on_limited_radps(-0.2, 2.6, 1.2121, 2.55, 0.5), -0.2);
  EXPECT_EQ(run_on_limited_radps(0.2, 1.1, 1.2121, 2.55, 0.5), 0.2);
  // No dead man's switch (dog = 0): nothing bounds a run-on, the command stays.
  EXPECT_EQ(run_on_limited_radps(2.0, 2.5, 1.2121, 2.55, 0.0), 2.0);
  // A joint running 0.2 rad/s faster than its no-load velocity runs on that much faster: the
  // limit comes down by 0.2 rad/s; a loaded one running 0.2 rad/s slower may be commanded that
  // much more (its run-on is the same).
  EXPECT_DOUBLE_EQ(run_on_limited_radps(2.0, 2.0, 1.2121, 2.55, 0.5, 0.2), 0.55 / 0.5 - 0.2);
  EXPECT_DOUBLE_EQ(run_on_limited_radps(2.0, 2.0, 1.2121, 2.55, 0.5, -0.2), 0.55 / 0.5 + 0.2);
  EXPECT_DOUBLE_EQ(run_on_limited_radps(-2.0, 2.0, 1.2121, 2.55, 0.5, 0.2),
                   -(2.0 - 1.2121) / 0.5 - 0.2);
  EXPECT_DOUBLE_EQ(run_on_limited_radps(-2.0, 2.0, 1.2121, 2.55, 0.5, -0.2),
                   -(2.0 - 1.2121) / 0.5 + 0.2);
  // A load that alone runs the joint to the bound in T_run: no command toward it at all.
  EXPECT_EQ(run_on_limited_radps(0.5, 2.5, 1.2121, 2.55, 0.5, 0.2), 0.0);
  EXPECT_THROW(run_on_limited_radps(1.0, 2.0, 1.2121, 2.55, -0.1), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(
    DrawnUnits, JointBoundsOnEveryUnit,
    ::testing::Values(Unit{1.0, 1.0, 0.012}, Unit{0.85, 1.1, 0.014}, Unit{0.85, 0.9, 0.010},
                      Unit{1.15, 1.1, 0.014}, Unit{1.15, 0.9, 0.010}));

TEST(JointMargin, ThePositiveBoundsComeInByTheGapsUncertaintyAsFarAsTheShaftHasCrossed) {
  const Params params;
  const JointParams full = joint_bounds_with_backlash_margin(params.joints, params.motors);
  EXPECT_NEAR(full.front_max_rad, -1.2121 - 0.15 * 0.052, 1e-12);
  EXPECT_NEAR(full.rear_max_rad, 2.55 - 0.15 * 0.250, 1e-12);
  EXPECT_EQ(full.front_min_rad, params.joints.front_min_rad);
  EXPECT_EQ(full.rear_min_rad, params.joints.rear_min_rad);
  // The shaft at the gap's negative end: no margin; halfway across: half; pushing: all of it.
  EXPECT_EQ(positive_bound_margin_rad(0.15, 0.25, 2.0, 2.0), 0.0);
  EXPECT_NEAR(positive_bound_margin_rad(0.15, 0.25, 2.125, 2.0), 0.01875, 1e-12);
  EXPECT_NEAR(positive_bound_margin_rad(0.15, 0.25, 2.3, 2.0), 0.0375, 1e-12);
  EXPECT_EQ(positive_bound_margin_rad(0.15, 0.0, 1.0, 1.0), 0.0);  // the wheels have no gap
  JointParams narrow = params.joints;
  narrow.backlash_uncertainty = 0.5;
  narrow.rear_max_rad = narrow.rear_min_rad + 0.1;
  EXPECT_THROW(joint_bounds_with_backlash_margin(narrow, params.motors), std::invalid_argument);
}

// A start-up through its first two phases (every controller configured, µ8's switch armed):
// Procedure 4.3 next.
Startup calibrating(const Params& params) {
  Startup startup(params);
  for (std::size_t i = 0; i < kMotorCount; ++i) startup.on_configured(i);
  startup.on_dead_man_acknowledged();
  return startup;
}

// Procedure 4.3's meeting of shaft and joint: free at ν, the gap closes when w̄ < ν/2.
TEST(StartupProcedure43, TheGapClosesWhereTheShaftMeetsItsJointNotAfterTheConfiguredGap) {
  const Params params;
  Startup startup = calibrating(params);
  const double h = params.cycle.period_s;
  const double nu = -0.14;
  std::array<double, 2> shaft{-1.2121, 1.2121};
  // The rear shaft runs free for 0.20 rad (a gap 20 % narrower than 0.25), then drags its joint
  // at a quarter of ν; the front one meets its joint after 0.05 rad.
  std::array<double, 2> travelled{};
  int k = 0;
  std::array<double, 2> duty{-1.0, -1.0};
  for (; k < 400 && startup.phase() == StartupPhase::kCalibrate; ++k) {
    std::array<double, 2> speed{};
    for (std::size_t j = 0; j < 2; ++j) {
      const double free_travel = j == 0 ? 0.05 : 0.20;
      speed[j] = duty[j] == 0.0 ? 0.0 : (travelled[j] < free_travel ? nu : nu / 4.0);
    }
    duty = startup.calibrate(k * h, shaft, speed, {nu, nu});
    for (std::size_t j = 0; j < 2; ++j) {
      const double v = duty[j] == 0.0 ? 0.0 : speed[j];
      shaft[j] += v * h;
      travelled[j] -= v * h;
    }
  }
  EXPECT_EQ(startup.phase(), StartupPhase::kDone);
  // Stopped within two cycles of dragging (0.035 rad/s): not the 0.05 more of b = 0.25.
  EXPECT_GT(travelled[1], 0.20);
  EXPECT_LT(travelled[1], 0.20 + 3 * 0.035 * h);
  EXPECT_LT(travelled[0], 0.05 + 3 * 0.035 * h);
  // What the shafts dragged their joints: counted from the last free reading, so within one
  // cycle's free travel (0.14 rad/s · h) of the truth.
  const auto dragged = startup.over_travel_rad();
  EXPECT_NEAR(dragged[0], travelled[0] - 0.05, 0.14 * h);
  EXPECT_NEAR(dragged[1], travelled[1] - 0.20, 0.14 * h);
}

// On soft ground a joint gives way: dragged, the shaft runs at 0.8 of its free speed and never
// slows to ν/2. The meeting is found against the crossing's own speed, within a few cycles, and
// the drag is counted; a cycle's duty shows in the next cycle's readings. (With ν/2 alone
// the shaft ran on to the widest gap, 1.15·0.25, and dragged the joint 0.0875 rad.)
TEST(StartupProcedure43, AJointThatGivesWayIsMetAgainstTheCrossingsOwnSpeedAndItsDragCounted) {
  const Params params;
  Startup startup = calibrating(params);
  const double h = params.cycle.period_s;
  const double nu = -0.15;
  const std::array<double, 2> free_travel{0.03, 0.20};
  std::array<double, 2> shaft{-1.2121, 1.2121};
  std::array<double, 2> joint = shaft;
  std::array<double, 2> read_shaft = shaft;
  std::array<double, 2> read_speed{};
  std::array<double, 2> duty{-1.0, -1.0};
  for (int k = 0; k < 400 && startup.phase() == StartupPhase::kCalibrate; ++k) {
    duty = startup.calibrate(k * h, read_shaft, read_speed, {nu, nu});
    for (std::size_t j = 0; j < 2; ++j) {
      const bool met = shaft[j] <= joint[j] - free_travel[j];
      // ±1 count of 0.0017 rad/s on the free readings, as the encoders give them.
      const double speed = duty[j] == 0.0 ? 0.0 : (met ? 0.8 * nu : nu + 0.0017 * (k % 3 - 1));
      shaft[j] += speed * h;
      if (met) joint[j] += speed * h;
      read_speed[j] = speed;  // what this cycle's duty did, read with the next request
    }
    read_shaft = shaft;
  }
  EXPECT_EQ(startup.phase(), StartupPhase::kDone);
  const auto dragged = startup.over_travel_rad();
  for (std::size_t j = 0; j < 2; ++j) {
    const double truth = std::array<double, 2>{-1.2121, 1.2121}[j] - joint[j];
    EXPECT_GT(truth, 0.0) << j;
    EXPECT_LT(truth, 4 * 0.8 * 0.15 * h) << j << ": found within four cycles of dragging";
    EXPECT_NEAR(dragged[j], truth, 0.15 * h) << j;
  }
}

TEST(StartupProcedure43, OnASlopeAShaftThatNeverSlowsStopsAtTheNarrowestGap) {
  const Params params;
  for (const bool on_slope : {false, true}) {
    Startup startup = calibrating(params);
    const double h = params.cycle.period_s;
    std::array<double, 2> shaft{-1.2121, 1.2121};
    std::array<double, 2> duty{-1.0, -1.0};
    for (int k = 0; k < 400 && startup.phase() == StartupPhase::kCalibrate; ++k) {
      std::array<double, 2> speed{duty[0] == 0.0 ? 0.0 : -0.14, duty[1] == 0.0 ? 0.0 : -0.14};
      duty = startup.calibrate(k * h, shaft, speed, {-0.14, -0.14}, on_slope);
      shaft[1] += speed[1] * h;
    }
    const double travel = 1.2121 - shaft[1];
    const double limit = (on_slope ? 0.85 : 1.15) * 0.25;
    if (on_slope) {
      // The narrowest gap keeps the joint inside (5.3): anticipated by the shaft's run-on after
      // the decision, 0.14 rad/s over the dead time and a cycle, which this plant (stopping at
      // once) does not have.
      const double run_on = 0.14 * (joint_dead_time_s(params) + h);
      EXPECT_LT(travel, limit) << on_slope;
      EXPECT_GE(travel, limit - run_on - 0.14 * h) << on_slope;
    } else {
      EXPECT_GE(travel, limit) << on_slope;
      EXPECT_LT(travel, limit + 2 * 0.14 * h + 1e-9) << on_slope;  // the test moves a cycle late
    }
    EXPECT_EQ(startup.over_travel_rad()[1], 0.0) << on_slope << ": it met no joint";
  }
}

// After a restart the rear joint stands 0.03 rad above p7_min with its shaft engaged at the
// negative end of the gap (a gait contracted it there): a shaft that never slows may travel only
// p̄ − p7_min = 0.03 rad, not the widest gap, and one already past the bound not at all.
TEST(StartupProcedure43, ARestartedShaftDoesNotDragItsJointPastTheNegativeBound) {
  const Params params;
  for (const double start : {1.2121 + 0.03, 1.2121 - 0.004}) {
    Startup startup(params);
    startup.continue_joints();
    for (std::size_t i = 0; i < kMotorCount; ++i) startup.on_configured(i);
    startup.on_dead_man_acknowledged();
    const double h = params.cycle.period_s;
    std::array<double, 2> shaft{-1.8, start};
    EXPECT_EQ(startup.calibrate(0.0, shaft, {}, {}), (std::array<double, 2>{0.0, 0.0}))
        << "the kept state not judged yet: at rest";
    startup.take_joints({shaft[0] - params.joints.front_min_rad,
                         shaft[1] - params.joints.rear_min_rad});
    std::array<double, 2> duty{-1.0, -1.0};
    for (int k = 0; k < 400 && startup.phase() == StartupPhase::kCalibrate; ++k) {
      std::array<double, 2> speed{duty[0] == 0.0 ? 0.0 : -0.14, duty[1] == 0.0 ? 0.0 : -0.14};
      duty = startup.calibrate(k * h, shaft, speed, {-0.14, -0.14});
      shaft[1] += speed[1] * h;
    }
    EXPECT_EQ(startup.phase(), StartupPhase::kDone);
    EXPECT_GE(shaft[1], std::min(start, params.joints.rear_min_rad) - 2 * 0.14 * h - 1e-9)
        << start;  // the test moves a cycle late
  }
}

// A shaft at rest shows no speed to anticipate its run-on by: the duties sent before its readings
// show motion carry it on regardless. Seed 8's soak: a restarted rear shaft allowed 0.0014 rad
// ran 0.0054. The plant: each duty turns the shaft at its free speed by (4.3) spread over the
// next cycles by the δ table of (4.4) (the response the driver's dead time is the mean of), read
// a cycle late. Whatever it is allowed, no shaft passes its negative bound: a take-up allowed
// less than free_run_on_rad() does not start, one allowed more runs and stops inside it.
TEST(StartupProcedure43, ARestartedShaftAllowedLessThanAStartFromRestRunsOnDoesNotStart) {
  const Params params;
  const double h = params.cycle.period_s;
  const adaptation::MotorCurve curve(
      adaptation::select_motor_curve(params.motor_curves, params.cycle.icr));
  const double u = params.motors.nominal_supply_v;
  const std::array<double, 2> free_speed{
      adaptation::no_load_velocity(curve, params.operator_input.calibration_duty,
                                   params.motors.scale[kFrontJoint], u, u),
      adaptation::no_load_velocity(curve, params.operator_input.calibration_duty,
                                   params.motors.scale[kRearJoint], u, u)};
  const std::vector<double>& delta =
      adaptation::select_response(params.responses, h, params.cycle.con).delta;
  const Startup probe(params);
  const double run_on_s = joint_dead_time_s(params) + h;
  for (std::size_t j = 0; j < 2; ++j) {
    EXPECT_GT(free_speed[j], 0.13) << "Procedure 4.3 measured 0.13–0.15 rad/s at d = −0.08";
    EXPECT_LT(free_speed[j], 0.16);
    EXPECT_NEAR(probe.free_run_on_rad()[j], free_speed[j] * run_on_s, 1e-12);
  }
  const std::array<double, 2> lowest{params.joints.front_min_rad, params.joints.rear_min_rad};
  const double min_start = probe.free_run_on_rad()[1];
  for (const double allowed : {-0.004, 0.0, 0.0014, 0.5 * min_start, 0.99 * min_start,
                               1.01 * min_start, 1.5 * min_start, 3.0 * min_start}) {
    Startup startup(params);
    startup.continue_joints();
    for (std::size_t i = 0; i < kMotorCount; ++i) startup.on_configured(i);
    startup.on_dead_man_acknowledged();
    const std::array<double, 2> start{lowest[0] + 0.5, lowest[1] + allowed};
    std::array<double, 2> shaft = start;
    startup.take_joints({0.5, allowed});
    EXPECT_FALSE(startup.take_up_skipped(0));
    EXPECT_EQ(startup.take_up_skipped(1), allowed < min_start) << allowed;
    EXPECT_EQ(startup.take_up_travel_rad(1), allowed);
    std::array<std::vector<double>, 2> sent;  // the duties sent, the latest last
    std::array<double, 2> read_shaft = shaft;
    std::array<double, 2> read_speed{};
    double time_s = 0.0;
    for (int k = 0; k < 400 && startup.phase() == StartupPhase::kCalibrate; ++k) {
      time_s = k * h;
      const auto duty = startup.calibrate(time_s, read_shaft, read_speed,
                                          {-free_speed[0], -free_speed[1]});
      for (std::size_t j = 0; j < 2; ++j) {
        sent[j].push_back(duty[j]);
        double speed = 0.0;
        for (std::size_t d = 0; d < delta.size() && d < sent[j].size(); ++d) {
          if (sent[j][sent[j].size() - 1 - d] != 0.0) speed -= delta[d] * free_speed[j];
        }
        shaft[j] += speed * h;
        read_speed[j] = speed;  // what the duties did, read with the next request
      }
      read_shaft = shaft;
    }
    EXPECT_EQ(startup.phase(), StartupPhase::kDone) << allowed;
    EXPECT_LT(time_s, 1.0) << allowed << ": both shafts stopped, not timed out";
    EXPECT_GE(shaft[1], std::min(start[1], lowest[1])) << allowed << ": the bound holds";
    if (allowed < min_start) {
      EXPECT_EQ(shaft[1], start[1]) << allowed << ": not started";
    } else {
      EXPECT_LT(shaft[1], start[1] - 0.5 * min_start) << allowed << ": the take-up ran";
    }
  }
}

}  // namespace
}  // namespace marsokhod::driver
