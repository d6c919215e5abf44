// runner::run_soak and its parts: the segments, the random operator, the fault schedule, a short
// soak (deterministic, bit for bit), and a forced violation whose recording replays identically
// from the driver the soak had at the window's start.
#include "runner/soak.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "core/navigation/mission.hpp"
#include "runner/replay.hpp"
#include "runner/soak_segment.hpp"
#include "runner_test_support.hpp"

namespace marsokhod::runner {
namespace {

using testing::kConfigFile;
using testing::ScratchFolder;
using testing::shipped_params;

constexpr std::int64_t kCycleUs = 15600;

std::size_t line_count(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

TEST(SoakSegments, AnHourIsSixTenMinuteSegmentsAlternatingHardGroundAndSand) {
  const auto plans = plan_segments(1.0, 7, 600.0, 0.0156);
  ASSERT_EQ(plans.size(), 6u);
  for (std::size_t i = 0; i < plans.size(); ++i) {
    EXPECT_EQ(plans[i].index, i);
    EXPECT_EQ(plans[i].sand, i % 2 == 1);
    EXPECT_EQ(plans[i].duration_us % kCycleUs, 0);
    EXPECT_NEAR(static_cast<double>(plans[i].duration_us), 600e6, kCycleUs);
    if (i > 0) {
      EXPECT_EQ(plans[i].start_us, plans[i - 1].start_us + plans[i - 1].duration_us);
    }
  }
  EXPECT_NE(plans[0].seed, plans[1].seed);
  EXPECT_EQ(plan_segments(1.0, 7, 600.0, 0.0156)[3].seed, plans[3].seed);
  const auto short_run = plan_segments(0.05, 7, 600.0, 0.0156);  // 3 min: 90 s on each ground
  ASSERT_EQ(short_run.size(), 2u);
  EXPECT_FALSE(short_run[0].sand);
  EXPECT_TRUE(short_run[1].sand);
  EXPECT_NEAR(static_cast<double>(short_run[1].duration_us), 90e6, kCycleUs);
}

// What an operator script sends for `minutes`, as one hash, and its statistics.
std::pair<std::size_t, OperatorStats> script_run(std::uint64_t seed, double minutes,
                                                 std::size_t* gamepad_inputs = nullptr) {
  OperatorScript script(seed, shipped_params());
  driver::DriverStatus status;
  std::size_t hash = 0;
  const auto mix = [&hash](double v) { hash = hash * 1000003u ^ std::hash<double>{}(v); };
  for (std::int64_t t = 0; t < static_cast<std::int64_t>(minutes * 60e6); t += kCycleUs) {
    status.faults.clear();
    if (t % 60000000 < 2000000) status.faults = {"µ3 silent"};  // a fault now and then
    const driver::OperatorInput* in = script.next(t, status);
    mix(in == nullptr ? -1.0 : in->stop + 2.0 * in->clear_faults);
    if (in == nullptr) continue;
    if (in->targets) {
      mix(in->targets->v1_radps + 3 * in->targets->v2_radps + 5 * in->targets->v6_radps);
      mix(static_cast<double>(in->targets->gait) + in->targets->gait_speed);
    }
    if (in->gamepad) {
      if (gamepad_inputs != nullptr) ++*gamepad_inputs;
      for (double a : in->gamepad->axes) mix(a);
    }
    if (in->velocity) mix(in->velocity->v_mps + 3 * in->velocity->yaw_radps);
    if (in->mission) {
      mix(static_cast<double>(in->mission->kind) + in->mission->angle_rad +
          in->mission->distance_m + in->mission->settle_s.value_or(-1.0));
      for (const navigation::Waypoint& w : in->mission->waypoints) mix(w.x_m + 3 * w.y_m);
    }
    mix(in->heartbeat ? 7.0 : 0.0);
  }
  return {hash, script.stats()};
}

// The missions and velocities the soak's operator sends are ones the driver takes: inside the
// limits check_request and check_velocity hold them to, a third of the missions with their own
// standing, every kind; a mission is followed by heartbeats.
TEST(SoakOperator, SendsMissionsAndVelocitiesTheDriverTakes) {
  const Params params = shipped_params();
  OperatorScript script(3, params);
  driver::DriverStatus status;
  // At the edge of the 1000 m the driver allows: the script's goto, up to 3 × 1.5 m further out
  // unclamped, must keep its waypoints inside.
  status.pose.x_m = 999.5;
  status.pose.y_m = -999.5;
  std::array<int, 3> kinds{};
  int missions = 0, own_standing = 0, velocities = 0;
  bool heartbeat_after_mission = false, mission_seen = false;
  for (std::int64_t t = 0; t < static_cast<std::int64_t>(60 * 60e6); t += kCycleUs) {
    const driver::OperatorInput* in = script.next(t, status);
    if (in == nullptr) continue;
    if (in->velocity) {
      ++velocities;
      EXPECT_FALSE(navigation::check_velocity(*in->velocity, params).has_value());
    }
    if (in->mission) {
      ++missions;
      mission_seen = true;
      EXPECT_FALSE(navigation::check_request(*in->mission).has_value())
          << navigation::check_request(*in->mission)->message;
      ++kinds[static_cast<std::size_t>(in->mission->kind) - 2];  // turn, move, goto
      if (in->mission->settle_s) ++own_standing;
    }
    if (in->heartbeat && mission_seen) heartbeat_after_mission = true;
  }
  EXPECT_GT(missions, 20);
  for (int k : kinds) EXPECT_GT(k, 0);
  EXPECT_GT(own_standing, 0);
  EXPECT_LT(own_standing, missions);
  EXPECT_GT(velocities, 0);
  EXPECT_TRUE(heartbeat_after_mission);
  EXPECT_GT(script.stats().heartbeats, 0u);
}

TEST(SoakOperator, DoesEverythingAnOperatorDoesAndTheSameForTheSameSeed) {
  std::size_t gamepad_inputs = 0;
  const auto [hash, stats] = script_run(11, 30.0, &gamepad_inputs);
  for (std::size_t a = 0; a < kActivityCount; ++a) {
    EXPECT_GT(stats.activities[a], 0u) << activity_name(static_cast<Activity>(a));
  }
  EXPECT_GT(stats.short_silences, 0u);
  EXPECT_GT(stats.long_silences, 0u);
  EXPECT_GT(stats.hand_overs, 0u);
  EXPECT_GT(stats.fault_clears, 0u);
  EXPECT_GT(gamepad_inputs, 0u);                            // a console with a gamepad
  EXPECT_LT(gamepad_inputs, stats.commands);                // and one that sends targets
  EXPECT_LT(stats.commands, static_cast<std::uint64_t>(30 * 60 / 0.0156));  // dropped ones
  EXPECT_EQ(script_run(11, 30.0).first, hash);
  EXPECT_NE(script_run(12, 30.0).first, hash);
}

TEST(SoakFaults, EveryKindIsInjectedAndSwitchedOffAgain) {
  sim::SimOptions options;
  options.seed = 5;
  sim::SimulatedRover rover(shipped_params(), options);
  FaultSchedule schedule(5);
  std::array<int, kFaultKindCount> on{}, off{};
  for (std::int64_t t = 0; t < 3600000000; t += kCycleUs) {
    for (const FaultChange& c : schedule.update(t, rover)) {
      ++(c.on ? on : off)[static_cast<std::size_t>(c.kind)];
      EXPECT_FALSE(c.what.empty());
    }
    const double loss = rover.faults().frame_loss_probability;
    ASSERT_TRUE(loss == 0.0 || loss == 0.01) << loss;
  }
  for (std::size_t k = 0; k < kFaultKindCount; ++k) {
    const char* name = fault_kind_name(static_cast<FaultKind>(k));
    EXPECT_GT(on[k], 0) << name;
    EXPECT_EQ(static_cast<std::uint64_t>(on[k]), schedule.injected()[k]) << name;
    if (static_cast<FaultKind>(k) != FaultKind::kBrownout) {
      EXPECT_GE(off[k], on[k] - 1) << name;  // all but one still on at the end
    }
  }
}

// A short soak: the rover on both grounds, faults, every invariant — no violation on today's
// driver for this seed, and the same run twice, bit for bit.
TEST(Soak, AShortSoakIsCleanAndDeterministic) {
  SoakOptions options;
  options.hours = 0.02;  // 72 s: 36 s on hard ground, 36 s on sand
  options.seed = 1;
  const SoakResult a = run_soak(shipped_params(), options);
  EXPECT_EQ(a.segments, 2u);
  EXPECT_EQ(a.cycles, 2u * 2308u);
  EXPECT_GT(a.evaluations, a.cycles * 6);
  EXPECT_GT(a.operator_stats.commands, 3000u);
  EXPECT_EQ(a.total_violations(), 0u) << a.first_violations.front().violation.detail;
  // The summary says where the joints came nearest (5.3)'s tolerance, in the soak's own time.
  ASSERT_GT(a.max_joint_excess_rad, 0.0);
  ASSERT_TRUE(a.max_joint_excess_at.has_value());
  char excess[48];
  std::snprintf(excess, sizeof excess, "is %.4f rad outside (5.3)", a.max_joint_excess_rad);
  EXPECT_NE(a.max_joint_excess_at->violation.detail.find(excess), std::string::npos)
      << a.max_joint_excess_at->violation.detail;
  // The soak's time is the segment's start (the first segment's 2308 cycles before the second)
  // plus the session's time.
  const double session_s = static_cast<double>(a.max_joint_excess_at->violation.time_us) * 1e-6;
  const double second_start_s = 2308 * shipped_params().cycle.period_s;
  EXPECT_NEAR(a.max_joint_excess_at->soak_time_s,
              (a.max_joint_excess_at->segment == 0 ? 0.0 : second_start_s) + session_s, 1e-9);
  EXPECT_LE(a.max_joint_excess_at->soak_time_s, 72.0);
  EXPECT_EQ(to_json(a)["max_joint_excess_at"]["detail"], a.max_joint_excess_at->violation.detail);
  const SoakResult b = run_soak(shipped_params(), options);
  auto same = [](nlohmann::ordered_json j) {
    j.erase("wall_time_s");
    j.erase("real_time_factor");
    return j.dump();
  };
  EXPECT_EQ(same(to_json(a)), same(to_json(b)));
}

// A checker with a deliberately low duty ceiling fails as soon as the operator drives; the
// window before it (1 s here, 30 s by default) replays identically from the soak's driver.
TEST(Soak, AViolationWritesAWindowThatReplaysFromTheSoaksDriver) {
  const ScratchFolder folder;
  SoakOptions options;
  options.hours = 0.01;
  options.seed = 4;
  options.window_s = 1.0;
  options.limits.duty_ceiling = 0.1;
  options.out = folder.path() / "violation";
  options.config_file = kConfigFile;
  std::vector<SoakViolation> reported;
  const SoakResult r =
      run_soak(shipped_params(), options, [&](const SoakViolation& v) { reported.push_back(v); });
  ASSERT_GT(r.violations[static_cast<std::size_t>(Invariant::kDutyBound)], 0u);
  ASSERT_FALSE(r.first_violations.empty());
  EXPECT_EQ(reported.size(), r.first_violations.size());
  const SoakViolation& first = r.first_violations.front();
  EXPECT_EQ(first.violation.invariant, Invariant::kDutyBound);
  EXPECT_NE(first.violation.detail.find("ceiling 0.1000"), std::string::npos) << first.violation.detail;
  // The summary's entry for it, its keys in their order.
  const auto summary = to_json(r).at("first_violations").at(0);
  std::vector<std::string> keys;
  for (const auto& item : summary.items()) keys.push_back(item.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"invariant", "soak_time_s", "segment", "terrain",
                                            "session_time_s", "detail"}));
  EXPECT_EQ(summary.at("invariant"), "duty-bound");
  EXPECT_EQ(summary.at("detail"), first.violation.detail);
  EXPECT_DOUBLE_EQ(summary.at("soak_time_s").get<double>(), first.soak_time_s);
  ASSERT_TRUE(r.recording.has_value());
  EXPECT_EQ(r.recording_note, "");  // the re-run found the same violation at the same cycle
  const auto dir = *r.recording;
  std::ifstream in(dir / "soak.json");
  const auto window = nlohmann::json::parse(in);
  EXPECT_EQ(window.at("violation_time_us").get<std::int64_t>(), first.violation.time_us);
  EXPECT_EQ(window.at("invariant"), "duty-bound");
  const auto start_us = window.at("window_start_us").get<std::int64_t>();
  EXPECT_GT(start_us, 0);  // the driver had been running for a while: a warm start is needed
  EXPECT_EQ(line_count(dir / "operator.jsonl"),
            static_cast<std::size_t>((first.violation.time_us - start_us) / kCycleUs + 1));
  auto driver = soak_window_driver(dir, shipped_params(), shipped_params());
  ASSERT_NE(driver, nullptr);
  EXPECT_EQ(driver->status().cycle, static_cast<std::uint64_t>(start_us / kCycleUs));
  const ReplayResult replayed = replay(dir, shipped_params(), std::move(driver));
  EXPECT_TRUE(replayed.identical) << replayed.first_difference;
  EXPECT_EQ(replayed.cycles, line_count(dir / "operator.jsonl"));
  // A fresh driver cannot replay it: it would configure the controllers first.
  EXPECT_FALSE(replay(dir, shipped_params()).identical);
}

}  // namespace
}  // namespace marsokhod::runner
