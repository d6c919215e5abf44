#include "core/navigation/mission.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <gtest/gtest.h>

namespace marsokhod::navigation {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kH = 0.0156;  // the driver's cycle
constexpr double kStood = 10.0;  // the rover stood long enough before the mission

// A skid-steered unicycle behind the ramp (4.14) of the driver: v1 and v2 approach their targets
// at μ rad/s², the body moves at r·v1 and turns at η·v2·r/(t/2) — η the share skidding leaves of
// the rolling turn (spin-efficiency: about a half on hard ground).
struct Plant {
  Plant(const Params& p, double eta = 0.5) : params(p), efficiency(eta) {}
  const Params& params;
  double efficiency;
  double v1 = 0.0, v2 = 0.0;
  estimation::Pose pose;

  void step(const DriveTargets& t) {
    const double mu = params.operator_input.drive_rate_per_s * kH;
    v1 += std::clamp(t.v1_radps - v1, -mu, mu);
    v2 += std::clamp(t.v2_radps - v2, -mu, mu);
    const double r = params.geometry.wheel_radius_m;
    const double speed = r * v1;
    const double yaw_rate = efficiency * v2 * r / (0.5 * params.geometry.track_width_m);
    pose.x_m += speed * std::cos(pose.heading_rad) * kH;
    pose.y_m += speed * std::sin(pose.heading_rad) * kH;
    pose.heading_rad += yaw_rate * kH;
    pose.speed_mps = speed;
    pose.yaw_rate_radps = yaw_rate;
  }
  // The driver's judgement: every bridge off and nothing turning.
  bool stands() const { return v1 == 0.0 && v2 == 0.0; }
};

// The plant on soft soil: once m2 has stopped, the soil's shear unloads and turns the rover
// back against its last turn by `rebound_rad` at 0.05 rad/s, its wheels turning with it (the
// driver sees the rover moving).
struct SoftPlant : Plant {
  SoftPlant(const Params& p, double eta, double rebound) : Plant(p, eta), rebound_rad(rebound) {}
  double rebound_rad;
  double turn_sign = 0.0;   // of the last turn
  double unloading = 0.0;   // rebound still to come
  void step(const DriveTargets& t) {
    const double before = v2;
    Plant::step(t);
    if (v2 != 0.0) turn_sign = v2 > 0.0 ? 1.0 : -1.0;
    if (before != 0.0 && v2 == 0.0) unloading = rebound_rad;
    const double back = std::min(unloading, 0.05 * kH);
    unloading -= back;
    pose.heading_rad -= turn_sign * back;
    pose.yaw_rate_radps -= turn_sign * back / kH;
  }
  bool stands() const { return Plant::stands() && unloading == 0.0; }
};

// Runs the mission until it ends or `limit_s` passes; returns the time it took.
template <typename P>
double run(MissionRunner& runner, P& plant, double limit_s) {
  double t = 0.0;
  while (runner.running() && t < limit_s) {
    t += kH;
    plant.step(runner.update(plant.pose, t, plant.stands()));
  }
  return t;
}

TEST(VelocityTargets, CmdVelMapsOntoM1AndM2WithTheGeometry) {
  const Params params;
  // 0.1 m/s on r = 0.125 m is v1 = 0.8 rad/s; 0.2 rad/s with the centre wheels 0.35 m off the
  // middle is v2 = 0.2·0.35/0.125 = 0.56 rad/s.
  const DriveTargets t = velocity_targets({0.1, 0.2}, params);
  EXPECT_NEAR(t.v1_radps, 0.8, 1e-12);
  EXPECT_NEAR(t.v2_radps, 0.56, 1e-12);
  // The limits are the operator's: r·v1ᵈ = 0.281 m/s, r·v2ᵈ/(t/2) = 0.536 rad/s.
  EXPECT_NEAR(max_velocity_mps(params), 0.125 * 2.25, 1e-12);
  EXPECT_NEAR(max_yaw_rate_radps(params), 0.125 * 1.5 / 0.35, 1e-12);
  EXPECT_FALSE(check_velocity({0.28, -0.5}, params));
  const auto e = check_velocity({0.3, 0.0}, params);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->field, "v_mps");
  EXPECT_NE(e->message.find("out of range"), std::string::npos);
  EXPECT_TRUE(check_velocity({0.0, std::nan("")}, params));
}

TEST(MissionRequest, BadRequestsNameTheirField) {
  MissionRequest turn{MissionKind::kTurn, 20.0, 0.0, {}, {}};
  ASSERT_TRUE(check_request(turn));
  EXPECT_EQ(check_request(turn)->field, "angle_rad");
  MissionRequest move{MissionKind::kMove, 0.0, std::nan(""), {}, {}};
  EXPECT_EQ(check_request(move)->field, "distance_m");
  MissionRequest empty{MissionKind::kGoto, 0.0, 0.0, {}, {}};
  EXPECT_EQ(check_request(empty)->field, "waypoints");
  MissionRequest far{MissionKind::kGoto, 0.0, 0.0, {{1.0, 2.0}, {1e4, 0.0}}, {}};
  EXPECT_EQ(check_request(far)->field, "waypoints[1].x_m");
  MissionRequest ok{MissionKind::kGoto, 0.0, 0.0, {{1.0, 2.0}}, {}};
  EXPECT_FALSE(check_request(ok));
  MissionRunner runner{Params{}};
  EXPECT_THROW(runner.start(far, {}, 0.0, kStood), std::invalid_argument);
  EXPECT_FALSE(runner.running());
}

TEST(MissionRunner, TurnReachesItsHeadingWithinTheTolerance) {
  const Params params;
  for (const double efficiency : {0.3, 0.5, 0.9}) {  // a slower and a faster turning ground
    for (const double angle : {kPi / 2, -kPi / 4, 2 * kPi}) {
      MissionRunner runner(params);
      Plant plant{params, efficiency};
      runner.start({MissionKind::kTurn, angle, 0.0, {}, {}}, plant.pose, 0.0, kStood);
      run(runner, plant, 120.0);
      EXPECT_EQ(runner.status().state, MissionState::kReached) << efficiency << " " << angle;
      // The loop stops at the heading, plus what the ramp carries it on, at most
      // v2_min²/(2μ)·η·r/(t/2) = 0.09/4·0.9·0.357 = 0.007 rad; a correction brings an overshoot
      // beyond twice the tolerance (0.5°) back.
      EXPECT_NEAR(plant.pose.heading_rad, angle, 2 * params.navigation.heading_tolerance_rad + 0.008)
          << efficiency << " " << angle;
      EXPECT_NEAR(plant.pose.x_m, 0.0, 1e-12);
      EXPECT_DOUBLE_EQ(runner.status().progress, 1.0);
    }
  }
}

// On soft soil a stopped rover turns back as the wheels' soil unloads (≈ 0.01 rad on the
// simulator's sand; odometry-square-sand). Here 1.5 times the tolerance: a turn stopped at the
// tolerance's near edge would settle 2.5 tolerances off, less the ramp's run-on (≤ 0.4 of the
// tolerance at η = 0.3), and so would each correction — two corrections, and still more than
// twice the tolerance off. Run to its heading, the turn settles within 1.5 tolerances.
TEST(MissionRunner, TurnRunsToItsHeadingSoThatTheSoilsReboundStaysWithinTheTolerance) {
  const Params params;
  const double tolerance = params.navigation.heading_tolerance_rad;
  for (const double efficiency : {0.3, 0.5}) {
    for (const double angle : {kPi / 2, -kPi / 2}) {
      MissionRunner runner(params);
      SoftPlant plant{params, efficiency, 1.5 * tolerance};
      runner.start({MissionKind::kTurn, angle, 0.0, {}, {}}, plant.pose, 0.0, kStood);
      run(runner, plant, 120.0);
      EXPECT_EQ(runner.status().state, MissionState::kReached) << efficiency << " " << angle;
      EXPECT_EQ(runner.status().corrections, 0) << efficiency << " " << angle;
      EXPECT_LE(std::abs(plant.pose.heading_rad - angle), 1.5 * tolerance + 1e-9)
          << efficiency << " " << angle;
    }
  }
}

// Standing is the driver's judgement (every bridge off, no motor turning), not the pose's speed:
// the dead reckoning counts the centre unit's pitch into the distance, and the accelerometer's
// noise makes the speed read up to 1 cm/s at rest (|speed|/r = 0.08 rad/s, past the still
// threshold of 0.03). A mission that must first stand settle_s drives after settle_s, not after
// max_settle_s; and it waits while the driver sees the wheels turn, whatever the pose reads.
TEST(MissionRunner, StandingIsTheDriversJudgementNotThePosesNoisySpeed) {
  const Params params;
  const double settle = params.navigation.settle_s;
  ASSERT_LT(settle + 0.5, params.navigation.max_settle_s);
  for (const bool wheels_turn_until_1s : {false, true}) {
    MissionRunner runner(params);
    estimation::Pose pose;
    runner.start({MissionKind::kMove, 0.0, 1.0, {}, {}}, pose, 0.0, 0.0);
    double t = 0.0, first_drive_s = -1.0;
    for (int k = 1; first_drive_s < 0.0 && t < 10.0; ++k) {
      t = k * kH;
      pose.speed_mps = (k % 2 == 0 ? 1.0 : -1.0) * 0.01;
      const bool stands = !(wheels_turn_until_1s && t < 1.0);
      if (runner.update(pose, t, stands).v1_radps != 0.0) first_drive_s = t;
    }
    const double stood_from = wheels_turn_until_1s ? 1.0 : 0.0;
    EXPECT_NEAR(first_drive_s, stood_from + settle + kH, kH + 1e-9) << wheels_turn_until_1s;
  }
}

TEST(MissionRunner, MoveDrivesItsDistanceAlongTheStartHeading) {
  const Params params;
  for (const double d : {2.0, -0.5, 0.05}) {
    MissionRunner runner(params);
    Plant plant{params};
    plant.pose.heading_rad = 0.3;
    runner.start({MissionKind::kMove, 0.0, d, {}, {}}, plant.pose, 0.0, kStood);
    ASSERT_EQ(runner.status().waypoints.size(), 1U);
    EXPECT_NEAR(runner.status().waypoints[0].x_m, d * std::cos(0.3), 1e-12);
    const double took = run(runner, plant, 60.0);
    EXPECT_EQ(runner.status().state, MissionState::kReached) << d;
    const double along = plant.pose.x_m * std::cos(0.3) + plant.pose.y_m * std::sin(0.3);
    // Within twice the position tolerance (a leg further off is driven again).
    EXPECT_NEAR(along, d, 2 * params.navigation.position_tolerance_m) << d;
    EXPECT_NEAR(plant.pose.heading_rad, 0.3, 0.01) << d;
    // 2 m at the cruise speed 0.15 m/s takes 13.3 s, with the ramps and the creep at most 15.5 s,
    // and then it stands settle_s.
    if (d == 2.0) {
      EXPECT_LT(took, 15.5 + params.navigation.settle_s);
    }
  }
}

TEST(MissionRunner, AMissionFirstStandsUntilTheRoverHasStoodSettleS) {
  const Params params;
  const double settle = params.navigation.settle_s;
  for (const double stood : {0.0, settle - 0.5, settle}) {
    MissionRunner runner(params);
    Plant plant{params};
    runner.start({MissionKind::kMove, 0.0, 1.0, {}, {}}, plant.pose, 0.0, stood);
    double t = 0.0, first_drive_s = -1.0;
    while (runner.running() && t < 60.0) {
      t += kH;
      const DriveTargets targets = runner.update(plant.pose, t, plant.stands());
      if (first_drive_s < 0.0 && targets.v1_radps != 0.0) first_drive_s = t;
      plant.step(targets);
    }
    EXPECT_EQ(runner.status().state, MissionState::kReached) << stood;
    // It drives once the standing before and in the mission make settle_s (one cycle after).
    EXPECT_NEAR(first_drive_s, std::max(settle - stood, 0.0) + kH, kH + 1e-9) << stood;
  }
  MissionRunner runner(params);
  EXPECT_THROW(runner.start({MissionKind::kMove, 0.0, 1.0, {}, {}}, {}, 0.0, -1.0),
               std::invalid_argument);
  EXPECT_FALSE(runner.running());
}

// A mission's own standing (settle_s): before its first leg and after each, in place of
// navigation.settle_s; the standing's limit grows by as much (4.5 s → 9 s: max 6 s → 10.5 s).
TEST(MissionRunner, AMissionsOwnSettleSIsHowLongItStands) {
  const Params params;
  const double own = 9.0;
  const double max_own = params.navigation.max_settle_s + own - params.navigation.settle_s;
  ASSERT_GT(own, params.navigation.max_settle_s);  // else the test could not tell them apart
  MissionRunner runner(params);
  Plant plant{params};
  MissionRequest request{MissionKind::kMove, 0.0, 1.0, {}, own};
  runner.start(request, plant.pose, 0.0, 2.0);
  EXPECT_EQ(runner.status().settle_s, own);
  double t = 0.0, first_drive_s = -1.0, stopped_s = -1.0;
  while (runner.running() && t < 60.0) {
    t += kH;
    const DriveTargets targets = runner.update(plant.pose, t, plant.stands());
    if (first_drive_s < 0.0 && targets.v1_radps != 0.0) first_drive_s = t;
    plant.step(targets);
    if (first_drive_s > 0.0 && stopped_s < 0.0 && plant.stands()) stopped_s = t;
  }
  ASSERT_EQ(runner.status().state, MissionState::kReached);
  // It drives once the 2 s stood before and the mission's standing make 9 s (a cycle after),
  EXPECT_NEAR(first_drive_s, own - 2.0 + kH, kH + 1e-9);
  // and ends 9 s after the wheels stop (the first cycle they stand counts as the first still).
  EXPECT_NEAR(runner.status().ended_s.value(), stopped_s + own, 2 * kH + 1e-9);
  // Never standing still (the wheels turn), the limit ends the standing: max_settle_s + 4.5 s.
  MissionRunner restless(params);
  restless.start(request, {}, 0.0, 0.0);
  double first = -1.0;
  for (int k = 1; first < 0.0 && k * kH < 30.0; ++k) {
    if (restless.update({}, k * kH, false).v1_radps != 0.0) first = k * kH;
  }
  EXPECT_NEAR(first, max_own + kH, kH + 1e-9);
  // Out of range or not finite: refused, naming the field; nothing starts.
  for (const double bad : {0.0, -1.0, kMaxSettleS + 0.1, std::nan("")}) {
    request.settle_s = bad;
    ASSERT_TRUE(check_request(request)) << bad;
    EXPECT_EQ(check_request(request)->field, "settle_s") << bad;
    MissionRunner refused(params);
    EXPECT_THROW(refused.start(request, {}, 0.0, kStood), std::invalid_argument);
    EXPECT_FALSE(refused.running());
  }
  request.settle_s = kMaxSettleS;
  EXPECT_FALSE(check_request(request));
}

TEST(MissionRunner, MoveHoldsItsLineAgainstADisturbance) {
  const Params params;
  MissionRunner runner(params);
  Plant plant{params};
  runner.start({MissionKind::kMove, 0.0, 3.0, {}, {}}, plant.pose, 0.0, kStood);
  double t = 0.0;
  while (runner.running() && t < 60.0) {
    t += kH;
    DriveTargets targets = runner.update(plant.pose, t, plant.stands());
    plant.step(targets);
    plant.pose.heading_rad += 0.02 * kH;  // a slope turning the rover left at 0.02 rad/s
  }
  EXPECT_EQ(runner.status().state, MissionState::kReached);
  EXPECT_NEAR(plant.pose.x_m, 3.0, 0.05);
  EXPECT_NEAR(plant.pose.y_m, 0.0, 0.05);  // pure pursuit pulls it back to the line
}

TEST(MissionRunner, GotoVisitsEveryWaypointInTurn) {
  const Params params;
  MissionRunner runner(params);
  Plant plant{params};
  const std::vector<Waypoint> square{{2.0, 0.0}, {2.0, 2.0}, {0.0, 2.0}, {0.0, 0.0}};
  runner.start({MissionKind::kGoto, 0.0, 0.0, square, {}}, plant.pose, 0.0, kStood);
  EXPECT_DOUBLE_EQ(runner.status().progress, 0.0);
  std::size_t leg = 0;
  double t = 0.0, closest_to_corner = 1e9;
  while (runner.running() && t < 200.0) {
    t += kH;
    plant.step(runner.update(plant.pose, t, plant.stands()));
    EXPECT_GE(runner.status().leg, leg);  // never back
    leg = runner.status().leg;
    if (leg == 1) closest_to_corner = std::min(closest_to_corner, std::hypot(plant.pose.x_m - 2.0, plant.pose.y_m));
  }
  EXPECT_EQ(runner.status().state, MissionState::kReached);
  EXPECT_EQ(runner.status().leg, 3U);
  EXPECT_LT(closest_to_corner, 0.05);
  EXPECT_NEAR(plant.pose.x_m, 0.0, 0.05);
  EXPECT_NEAR(plant.pose.y_m, 0.0, 0.05);
  // Four left turns of 90°.
  EXPECT_NEAR(plant.pose.heading_rad, 3 * kPi / 2, 0.1);
}

TEST(MissionRunner, NoProgressAbortsWithTheReason) {
  const Params params;
  MissionRunner runner(params);
  estimation::Pose stuck;  // a rover that never moves
  runner.start({MissionKind::kMove, 0.0, 1.0, {}, {}}, stuck, 0.0, kStood);
  double t = 0.0;
  DriveTargets last;
  while (runner.running() && t < 30.0) {
    t += kH;
    last = runner.update(stuck, t, false);  // its wheels driven
  }
  EXPECT_EQ(runner.status().state, MissionState::kAborted);
  EXPECT_NEAR(t, params.navigation.no_progress_s, 2 * kH);
  EXPECT_NE(runner.status().reason.find("no progress for 10 s (1 m still to go)"), std::string::npos)
      << runner.status().reason;
  EXPECT_EQ(last.v1_radps, 0.0);
}

TEST(MissionRunner, AbortAndReplaceEndTheRunningMission) {
  const Params params;
  MissionRunner runner(params);
  runner.start({MissionKind::kTurn, 1.0, 0.0, {}, {}}, {}, 0.0, kStood);
  EXPECT_EQ(runner.status().id, 1U);
  runner.start({MissionKind::kMove, 0.0, 1.0, {}, {}}, {}, 1.0, kStood);
  EXPECT_EQ(runner.status().id, 2U);
  EXPECT_EQ(runner.status().kind, MissionKind::kMove);
  runner.abort("the operator took over", 2.0);
  EXPECT_EQ(runner.status().state, MissionState::kAborted);
  EXPECT_EQ(runner.status().reason, "the operator took over");
  EXPECT_EQ(runner.update({}, 2.1, true).v1_radps, 0.0);
  runner.follow_velocity(3.0);
  runner.follow_velocity(3.1);  // the same stream
  EXPECT_EQ(runner.status().id, 3U);
  EXPECT_EQ(runner.status().kind, MissionKind::kVelocity);
  EXPECT_TRUE(runner.running());
  EXPECT_FALSE(runner.driving_mission());
}

TEST(MissionRunner, NonFinitePoseIsRejected) {
  MissionRunner runner{Params{}};
  runner.start({MissionKind::kMove, 0.0, 1.0, {}, {}}, {}, 0.0, kStood);
  estimation::Pose bad;
  bad.x_m = std::nan("");
  EXPECT_THROW(runner.update(bad, 0.1, true), std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::navigation
