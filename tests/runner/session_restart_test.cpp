// A driver restarted after a brown-out (runner/session.hpp, driver/joint_memory.hpp): it continues
// from the joint state its predecessor kept instead of taking bent joints to be vertical, its
// estimate stays as close to the truth as before, and the joints stay inside (5.3) when the gait
// goes on.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/estimation/odometry_frame.hpp"
#include "runner/session.hpp"
#include "runner_test_support.hpp"

namespace marsokhod::runner {
namespace {

using testing::shipped_params;

driver::OperatorInput gait_input(double speed) {
  driver::OperatorInput input;
  mobility::OperatorTargets targets;
  targets.gait = mobility::Gait::kRolking;
  targets.gait_speed = speed;
  input.targets = targets;
  return input;
}

struct JointErrors {
  double estimate_rad = 0.0;  // max |p − truth| of the two joints
  double excess_rad = 0.0;    // max excess of the truth beyond (5.3)
};

JointErrors joint_errors(const Session& session, const Params& params) {
  const auto truth = session.rover().truth().joint_angle_rad;
  const auto& s = session.status();
  const JointParams& j = params.joints;
  JointErrors e;
  e.estimate_rad = std::max(std::abs(s.motors[kFrontJoint].position_rad - truth[kFrontJoint]),
                            std::abs(s.motors[kRearJoint].position_rad - truth[kRearJoint]));
  e.excess_rad = std::max({j.front_min_rad - truth[kFrontJoint], truth[kFrontJoint] - j.front_max_rad,
                           j.rear_min_rad - truth[kRearJoint], truth[kRearJoint] - j.rear_max_rad});
  return e;
}

// Runs for `seconds` with `input` every cycle; returns the largest errors seen: the estimate's
// while driving, the truth's excess over (5.3) in every cycle (the driver down or starting too).
JointErrors run(Session& session, const Params& params, const driver::OperatorInput& input,
                double seconds) {
  JointErrors worst;
  const auto cycles = static_cast<int>(seconds / params.cycle.period_s);
  for (int k = 0; k < cycles; ++k) {
    session.step(&input);
    const JointErrors e = joint_errors(session, params);
    worst.excess_rad = std::max(worst.excess_rad, e.excess_rad);
    if (!session.driver_running() || session.status().mode != driver::DriverMode::kDriving) continue;
    worst.estimate_rad = std::max(worst.estimate_rad, e.estimate_rad);
  }
  return worst;
}

class SessionRestart : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(SessionRestart, ContinuesFromTheKeptJointsAfterABrownOut) {
  const Params& params = shipped_params();
  sim::SimOptions options;
  options.seed = GetParam();
  Session session(params, options);
  run(session, params, gait_input(0.0), 2.5);
  // Rolking until both joints stand well away from Remark 3.1's vertical position.
  const JointErrors before = run(session, params, gait_input(1.0), 7.0);
  const auto truth = session.rover().truth().joint_angle_rad;
  const auto& p0 = params.motors.initial_position_rad;
  ASSERT_GT(std::max(std::abs(truth[kFrontJoint] - p0[kFrontJoint]),
                     std::abs(truth[kRearJoint] - p0[kRearJoint])),
            0.3);
  const JointErrors last = joint_errors(session, params);
  session.rover().force_brownout();
  // The computer reboots (30 s); the operator goes on asking for the gait. The motors ran on
  // at their last duties for µ8's delay (0.26 s): the driver had limited its joint commands for
  // that (joint_margin.hpp), so the joints stopped inside (5.3).
  EXPECT_LE(run(session, params, gait_input(1.0), 31.0).excess_rad, 0.01);
  ASSERT_TRUE(session.driver_running());
  EXPECT_EQ(session.driver_restarts(), 1U);
  double startup_excess_rad = 0.0;
  while (session.status().mode == driver::DriverMode::kStartup) {
    session.step(nullptr);
    startup_excess_rad = std::max(startup_excess_rad, joint_errors(session, params).excess_rad);
  }
  EXPECT_LE(startup_excess_rad, 0.01) << "the take-up of the gaps dragged a joint out of (5.3)";
  const auto& s = session.status();
  EXPECT_TRUE(s.joints_known);
  EXPECT_EQ(s.joint_origin.rfind("kept across a restart (µ6 moved ", 0), 0U) << s.joint_origin;
  // The estimate is as good as before the brown-out: the shafts' coasting while µ8's switch
  // stopped them is in the counts, and (4.1) along it; what the driver did not know before (the
  // unit's true gap against the configured one) it does not know after.
  const JointErrors restored = joint_errors(session, params);
  EXPECT_LE(restored.estimate_rad, std::max(last.estimate_rad, before.estimate_rad) + 0.005)
      << "before the brown-out " << last.estimate_rad << " rad";
  const JointErrors after = run(session, params, gait_input(1.0), 12.0);
  EXPECT_LE(after.excess_rad, 0.01);
  EXPECT_LE(after.estimate_rad, before.estimate_rad + 0.01);
}

INSTANTIATE_TEST_SUITE_P(Units, SessionRestart, ::testing::Range<std::uint64_t>(1, 11));

driver::OperatorInput drive_input(double v1_radps, double v2_radps) {
  driver::OperatorInput input;
  mobility::OperatorTargets targets;
  targets.v1_radps = v1_radps;
  targets.v2_radps = v2_radps;
  input.targets = targets;
  return input;
}

// Steps with `input` for `seconds`, the tracker following the truth (as `marsokhod run` does for
// the console's map).
void follow(Session& session, estimation::OdometryFrameTracker& tracker,
            const driver::OperatorInput* input, double seconds) {
  const long cycles = std::lround(seconds / (static_cast<double>(session.cycle_us()) * 1e-6));
  for (long k = 0; k < cycles; ++k) follow_truth_odometry(session, session.step(input), tracker);
}

TEST(SessionTruthOdometry, TheTruthIsInTheFrameOfTheDriversLatestStart) {
  const Params& params = shipped_params();
  Session session(params, sim::SimOptions{});
  estimation::OdometryFrameTracker tracker;
  const double cycle_s = static_cast<double>(session.cycle_us()) * 1e-6;
  while (session.status().mode != driver::DriverMode::kDriving) {
    ASSERT_LT(session.time_s(), 10.0) << "the driver did not start up";
    follow(session, tracker, nullptr, cycle_s);
  }
  const auto near_pose = [&](double tolerance_m) {
    const estimation::PlanarPose truth = tracker.pose();
    const estimation::Pose& pose = session.status().pose;
    EXPECT_NEAR(truth.x_m, pose.x_m, tolerance_m);
    EXPECT_NEAR(truth.y_m, pose.y_m, tolerance_m);
    EXPECT_NEAR(truth.heading_rad, pose.heading_rad, 0.15);
  };
  // A spin to the left, then forward: the first frame's x is the start heading.
  const driver::OperatorInput spin = drive_input(0.0, 1.0);
  const driver::OperatorInput forward = drive_input(1.5, 0.0);
  follow(session, tracker, &spin, 2.0);
  follow(session, tracker, &forward, 3.0);
  ASSERT_GT(tracker.pose().heading_rad, 0.3);
  ASSERT_GT(std::hypot(tracker.pose().x_m, tracker.pose().y_m), 0.3);
  near_pose(0.1);
  // A brown-out: the restarted driver starts a new frame where its start-up ends, facing where
  // the rover faces then, and so does the truth.
  session.rover().force_brownout();
  while (session.driver_restarts() == 0 || session.status().cycle != 1) {
    ASSERT_LT(session.time_s(), 60.0) << "the driver did not restart";
    follow(session, tracker, nullptr, cycle_s);
  }
  EXPECT_EQ(tracker.pose().x_m, 0.0);
  EXPECT_EQ(tracker.pose().y_m, 0.0);
  EXPECT_EQ(tracker.pose().heading_rad, 0.0);
  while (session.status().startup_phase != driver::StartupPhase::kDone) {
    ASSERT_LT(session.time_s(), 70.0) << "the restarted driver did not start up";
    follow(session, tracker, nullptr, cycle_s);
  }
  // The start-up's last cycle was the origin; the rover stands.
  EXPECT_LT(std::hypot(tracker.pose().x_m, tracker.pose().y_m), 0.002);
  EXPECT_LT(std::abs(tracker.pose().heading_rad), 0.002);
  while (session.status().mode != driver::DriverMode::kDriving) {
    ASSERT_LT(session.time_s(), 70.0) << "the restarted driver did not start driving";
    follow(session, tracker, nullptr, cycle_s);
  }
  follow(session, tracker, &forward, 3.0);
  EXPECT_GT(tracker.pose().x_m, 0.3);
  near_pose(0.1);
}

}  // namespace
}  // namespace marsokhod::runner
