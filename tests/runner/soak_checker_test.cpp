// runner::InvariantChecker on hand-made cycles: a healthy stream passes, and each invariant is
// caught by a cycle that breaks it — and only just: one count or one cycle less passes.
#include "runner/soak_checker.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/protocol/codec.hpp"
#include "runner_test_support.hpp"

namespace marsokhod::runner {
namespace {

using testing::shipped_params;

constexpr std::int64_t kCycleUs = 15600;  // h of the shipped configuration

// A cycle the driver could have produced: every controller answered, the requests carry
// `duties`, the operator spoke, the joints and the supply are fine.
class CheckerTest : public ::testing::Test {
 protected:
  CheckerTest() : checker_(shipped_params()) {
    status_.mode = driver::DriverMode::kDriving;
    status_.startup_phase = driver::StartupPhase::kDone;
    status_.max_duty = 1.0;
    status_.cycle = 100;
  }

  static double counts(int pwm) { return static_cast<double>(pwm) / 511.0; }

  // One cycle at the next time step; returns its violations.
  std::vector<Violation> cycle(const MotorVector& duties, std::vector<std::size_t> silent = {}) {
    sent_.clear();
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      protocol::ControlRequest r;
      r.node = static_cast<std::uint8_t>(i);
      r.pwm = static_cast<std::uint16_t>(std::lround(std::abs(duties[i]) * 511));
      r.drv = duties[i] < 0.0 && r.pwm > 0;
      sent_.push_back(protocol::encode(r));
      status_.motors[i].duty = duties[i];
    }
    sent_.push_back(protocol::encode(protocol::MeasurementRequest{}));
    received_.clear();
    for (std::size_t i = 0; i <= kMotorCount; ++i) {
      if (std::find(silent.begin(), silent.end(), i) != silent.end()) continue;
      if (i < kMotorCount) {
        protocol::ControlResponse r;
        r.node = static_cast<std::uint8_t>(i);
        received_.push_back(protocol::encode(r));
      } else {
        protocol::MeasurementResponse m;
        m.vcc = vcc_;
        received_.push_back(protocol::encode(m));
      }
    }
    CycleView view = view_;
    view.time_us = time_us_;
    view.status = &status_;
    view.sent = sent_;
    view.received = received_;
    time_us_ += kCycleUs;
    return checker_.check(view);
  }
  std::vector<Violation> down_cycle() {
    CycleView view = view_;
    view.time_us = time_us_;
    view.driver_running = false;
    view.operator_command = false;
    time_us_ += kCycleUs;
    return checker_.check(view);
  }
  static bool has(const std::vector<Violation>& v, Invariant invariant) {
    return std::any_of(v.begin(), v.end(), [invariant](const Violation& x) { return x.invariant == invariant; });
  }
  // A few healthy cycles at rest, so that "previous" exists.
  void settle() {
    for (int k = 0; k < 3; ++k) ASSERT_TRUE(cycle({}).empty());
  }

  InvariantChecker checker_;
  driver::DriverStatus status_;
  CycleView view_ = [] {
    CycleView v;
    v.operator_command = true;
    v.joint_angle_rad = {-1.5, 1.5};
    return v;
  }();
  std::int64_t time_us_ = 0;
  std::uint16_t vcc_ = 970;  // 24.57 V
  std::vector<protocol::CanFrame> sent_, received_;
};

TEST_F(CheckerTest, AHealthyRampPasses) {
  settle();
  double d = 0.0;
  for (int k = 0; k < 30; ++k) {
    d = std::min(0.8, d + counts(26));  // the full step: round(0.05·511) = 26 counts
    const auto v = cycle({d, d, d, d, d, d, 0.0, 0.0});
    EXPECT_TRUE(v.empty()) << v.front().detail;
  }
  EXPECT_GT(checker_.evaluations(), 30u * 5u);
}

TEST_F(CheckerTest, NanInTheStatusIsCaught) {
  settle();
  status_.motors[4].load_radps = std::nan("");
  EXPECT_TRUE(has(cycle({}), Invariant::kFinite));
  status_.motors[4].load_radps = 0.0;
  status_.slope_rad = INFINITY;
  EXPECT_TRUE(has(cycle({}), Invariant::kFinite));
}

TEST_F(CheckerTest, DutyAboveTheBoundIsCaughtUnlessTheStepRuleHoldsItAbove) {
  settle();
  status_.max_duty = 0.3;
  for (int k = 0; k < 6; ++k) ASSERT_TRUE(cycle({counts(25 * (k + 1))}).empty()) << k;  // 150/511
  EXPECT_TRUE(cycle({counts(153)}).empty());                    // 0.2994 ≤ D
  EXPECT_TRUE(has(cycle({counts(155)}), Invariant::kDutyBound));  // 0.3033 > D + ½ count
  // D falls to 0.1: the duty may only fall by a step a cycle, and must.
  status_.max_duty = 0.1;
  EXPECT_TRUE(cycle({counts(155 - 26)}).empty());
  EXPECT_TRUE(has(cycle({counts(155 - 26 - 20)}), Invariant::kDutyBound));
}

TEST_F(CheckerTest, DutyAboveOneOrTheCeilingIsCaught) {
  InvariantChecker tight(shipped_params(), CheckerLimits{.duty_ceiling = 0.1});
  checker_ = tight;
  settle();
  EXPECT_TRUE(cycle({counts(26)}).empty());
  EXPECT_TRUE(cycle({counts(51)}).empty());  // 0.0998
  EXPECT_TRUE(has(cycle({counts(53)}), Invariant::kDutyBound));
}

TEST_F(CheckerTest, AJumpOrADirectionChangeAwayFromZeroIsCaught) {
  settle();
  EXPECT_TRUE(cycle({counts(26)}).empty());
  EXPECT_TRUE(has(cycle({counts(53)}), Invariant::kDutyStep));  // 27 counts
  EXPECT_TRUE(cycle({counts(30)}).empty());
  EXPECT_TRUE(cycle({counts(5)}).empty());
  EXPECT_TRUE(cycle({-counts(10)}).empty());                   // drv toggles at 0.0196 ≤ 0.02
  EXPECT_TRUE(cycle({counts(1)}).empty());
  EXPECT_TRUE(has(cycle({-counts(12)}), Invariant::kDutyStep));  // drv toggles at 0.0235
}

TEST_F(CheckerTest, AJointOutsideTheBoundsIsCaughtOnTheTruthOrTheEstimate) {
  settle();
  view_.joint_angle_rad = {-1.2121 + 0.0099, 1.5};
  EXPECT_TRUE(cycle({}).empty());
  view_.joint_angle_rad = {-1.5, 2.55 + 0.0102};
  EXPECT_TRUE(has(cycle({}), Invariant::kJointBounds));
  EXPECT_NEAR(checker_.max_joint_excess_rad(), 0.0102, 1e-9);
  // The rear encoder loses pulses: the driver cannot know the truth, its estimate must hold.
  view_.joint_encoder_fault = {false, true};
  status_.motors[kRearJoint].position_rad = 2.5;
  EXPECT_TRUE(cycle({}).empty());
  view_.joint_encoder_fault = {false, false};  // still judged on the estimate from then on
  status_.motors[kRearJoint].position_rad = 2.57;
  EXPECT_TRUE(has(cycle({}), Invariant::kJointBounds));
}

TEST_F(CheckerTest, TheLargestJointExcessIsKeptWithItsCycle) {
  settle();
  EXPECT_FALSE(checker_.max_joint_excess_at().has_value());  // inside (5.3): nothing to show
  view_.joint_angle_rad = {-1.5, 2.55 + 0.004};
  const std::int64_t first_us = time_us_;
  EXPECT_TRUE(cycle({}).empty());
  view_.joint_angle_rad = {-1.5, 2.55 + 0.002};  // less: the first stays the largest
  EXPECT_TRUE(cycle({}).empty());
  ASSERT_TRUE(checker_.max_joint_excess_at().has_value());
  EXPECT_EQ(checker_.max_joint_excess_at()->time_us, first_us);
  EXPECT_EQ(checker_.max_joint_excess_at()->invariant, Invariant::kJointBounds);
  EXPECT_NE(checker_.max_joint_excess_at()->detail.find("rear joint 2.5540 rad is 0.0040 rad"),
            std::string::npos)
      << checker_.max_joint_excess_at()->detail;
  // A larger one while the driver is down takes its place, and says so.
  view_.joint_angle_rad = {-2.55 - 0.007, 1.5};
  const std::int64_t down_us = time_us_;
  EXPECT_TRUE(down_cycle().empty());
  EXPECT_NEAR(checker_.max_joint_excess_rad(), 0.007, 1e-12);
  EXPECT_EQ(checker_.max_joint_excess_at()->time_us, down_us);
  EXPECT_NE(checker_.max_joint_excess_at()->detail.find("front joint -2.5570 rad is 0.0070 rad"),
            std::string::npos)
      << checker_.max_joint_excess_at()->detail;
  EXPECT_NE(checker_.max_joint_excess_at()->detail.find("while the driver is down"),
            std::string::npos);
}

TEST_F(CheckerTest, AnExcessPastTheToleranceIsReportedEvenWhenItIsNotTheLargest) {
  settle();
  view_.joint_angle_rad = {-1.5, 2.55 + 0.02};
  EXPECT_TRUE(has(cycle({}), Invariant::kJointBounds));
  view_.joint_angle_rad = {-1.5, 2.55 + 0.015};  // past 0.01, below the 0.02 before
  EXPECT_TRUE(has(cycle({}), Invariant::kJointBounds));
  EXPECT_NEAR(checker_.max_joint_excess_rad(), 0.02, 1e-12);
  view_.joint_angle_rad = {-2.55 - 0.012, 1.5};  // the same while the driver is down
  EXPECT_TRUE(has(down_cycle(), Invariant::kJointBounds));
  EXPECT_NEAR(checker_.max_joint_excess_rad(), 0.02, 1e-12);
  EXPECT_NEAR(checker_.max_down_joint_excess_rad(), 0.012, 1e-12);
  EXPECT_NE(checker_.max_joint_excess_at()->detail.find("rear joint 2.5700"), std::string::npos);
}

TEST_F(CheckerTest, ASilentControllerMustBeCountedAndReportedByTheThirdCycle) {
  settle();
  status_.bus.missed = 1;
  EXPECT_TRUE(cycle({}, {3}).empty());
  status_.bus.missed = 2;
  EXPECT_TRUE(cycle({}, {3}).empty());
  status_.bus.missed = 3;
  const auto third = cycle({}, {3});
  EXPECT_TRUE(has(third, Invariant::kSilentReported));
  EXPECT_FALSE(has(third, Invariant::kMissedCounted));
  status_.bus.missed = 4;
  status_.faults = {"µ3 silent"};
  EXPECT_TRUE(cycle({}, {3}).empty());
  // A missed response the status does not count.
  EXPECT_TRUE(has(cycle({}, {8}), Invariant::kMissedCounted));
}

TEST_F(CheckerTest, FaultModeMustRampEveryMotorDown) {
  settle();
  for (int k = 1; k <= 8; ++k) ASSERT_TRUE(cycle({counts(26 * k)}).empty());
  status_.mode = driver::DriverMode::kFault;
  EXPECT_TRUE(cycle({counts(26 * 7)}).empty());
  EXPECT_TRUE(has(cycle({counts(26 * 7)}), Invariant::kFaultStop));  // held, not stopping
}

TEST_F(CheckerTest, MotorsMustBeOffWhenTheControlledStopAfterTheTimeoutIsOver) {
  settle();
  view_.operator_command = false;  // the last command was the settle's last cycle
  const std::int64_t last_us = time_us_ - kCycleUs;
  // The timeout (0.5 s), the joints' (4.14) ramp ln 2/0.4 = 1.733 s, 20 cycles of duty steps
  // and 3 cycles for the sampled landings: 0.5 + 1.733 + 23·0.0156 = 2.592 s.
  const std::int64_t allowed_us = std::llround((0.5 + std::log(2.0) / 0.4 + 23 * 0.0156) * 1e6);
  while (time_us_ < last_us + allowed_us) {
    const auto v = cycle({counts(20)});
    ASSERT_TRUE(v.empty()) << time_us_;
  }
  EXPECT_TRUE(has(cycle({counts(20)}), Invariant::kOperatorStop));
  EXPECT_TRUE(cycle({}).empty());
  status_.mode = driver::DriverMode::kStartup;  // Procedure 4.3 moves the joints by itself
  EXPECT_TRUE(cycle({0, 0, 0, 0, 0, 0, -counts(10), -counts(10)}).empty());
}

TEST_F(CheckerTest, TheDeadMansSwitchMustStopTheMotorsWhenTheDriverIsDown) {
  settle();
  const std::int64_t last_us = time_us_ - kCycleUs;
  view_.motor_duty = {0.3};
  const std::int64_t dog = shipped_params().safety.dead_man_dog;
  while (time_us_ < last_us + dog * 262144 + kCycleUs) ASSERT_TRUE(down_cycle().empty());
  EXPECT_TRUE(has(down_cycle(), Invariant::kDeadMan));
  view_.motor_duty = {};
  EXPECT_TRUE(down_cycle().empty());
}

// µ8 sends its stop frames again every tick while the driver is silent: each of its frames to µi
// that the bus lost gives µi one tick more, and no more than that; lost frames before the driver
// went down do not count.
TEST_F(CheckerTest, ALostStopFrameGivesItsMotorOneTickMore) {
  view_.stop_frames_lost = {0, 0, 0, 0, 0, 5};  // lost while the driver ran
  settle();
  const std::int64_t last_us = time_us_ - kCycleUs;
  const std::int64_t dog = shipped_params().safety.dead_man_dog;
  const std::int64_t deadline_us = last_us + dog * 262144 + kCycleUs;
  view_.motor_duty = {0.0, 0.0, 0.0, 0.0, 0.0, 0.3};
  view_.stop_frames_lost[5] = 6;  // the first stop frame to µ5
  while (time_us_ < deadline_us + 262144) ASSERT_TRUE(down_cycle().empty()) << time_us_;
  const std::vector<Violation> late = down_cycle();
  ASSERT_TRUE(has(late, Invariant::kDeadMan));
  EXPECT_NE(late.front().detail.find("µ5 still at d = 0.3000"), std::string::npos)
      << late.front().detail;
  EXPECT_NE(late.front().detail.find("1 of µ8's stop frames to it lost"), std::string::npos)
      << late.front().detail;
  view_.stop_frames_lost[5] = 7;  // the repeat was lost too: one more tick
  EXPECT_TRUE(down_cycle().empty());
  view_.motor_duty[2] = 0.1;  // µ2's frames all arrived: it is late
  EXPECT_TRUE(has(down_cycle(), Invariant::kDeadMan));
}

TEST_F(CheckerTest, ARestartedDriverMustStartUpAfresh) {
  // The joints stand where the restarted driver's estimate puts them (see the next test).
  status_.motors[kFrontJoint].position_rad = -1.5;
  status_.motors[kRearJoint].position_rad = 1.5;
  settle();
  down_cycle();
  status_.cycle = 5;  // the old driver carried on
  EXPECT_TRUE(has(cycle({}), Invariant::kRestart));
  down_cycle();
  status_.cycle = 1;
  status_.mode = driver::DriverMode::kStartup;
  const auto v = cycle({});  // control requests, where a fresh driver configures first
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v.front().invariant, Invariant::kRestart);
}

TEST_F(CheckerTest, AJointThatRunsOnWhileTheDriverIsDownMustStayInsideTheBounds) {
  // The driver is down; µ6 runs on at its last duty. 0.009 rad past p6_min is within the
  // tolerance, 0.011 is not, and it is reported as the down time's excess.
  settle();
  view_.joint_angle_rad = {-2.559, 1.5};
  EXPECT_TRUE(down_cycle().empty());
  EXPECT_NEAR(checker_.max_down_joint_excess_rad(), 0.009, 1e-12);
  view_.joint_angle_rad = {-2.561, 1.5};
  const auto v = down_cycle();
  ASSERT_TRUE(has(v, Invariant::kJointBounds));
  EXPECT_NE(v.front().detail.find("while the driver is down"), std::string::npos);
  EXPECT_NEAR(checker_.max_down_joint_excess_rad(), 0.011, 1e-12);
  // A joint whose encoder lost pulses before: the driver steered by a wrong p, judged apart.
  view_.joint_encoder_fault = {false, true};
  view_.joint_angle_rad = {-1.5, 1.15};
  EXPECT_FALSE(has(down_cycle(), Invariant::kJointBounds));
  EXPECT_NEAR(checker_.max_unknown_joint_excess_rad(), 1.2121 - 1.15, 1e-12);
}

TEST_F(CheckerTest, ARestartedDriverIsHeldToTheBoundsFromItsFirstCycle) {
  settle();
  down_cycle();
  view_.joint_angle_rad = {-1.5, 1.2121 - 0.005};  // within the tolerance
  status_.cycle = 1;
  status_.mode = driver::DriverMode::kStartup;
  EXPECT_FALSE(has(cycle({}), Invariant::kJointBounds));
  view_.joint_angle_rad = {-1.5, 1.2121 - 0.02};  // no allowance for having been down
  EXPECT_TRUE(has(cycle({}), Invariant::kJointBounds));
}

TEST_F(CheckerTest, ALowSupplyMustBeWarnedAboutWithinThreeReadings) {
  settle();
  vcc_ = 902;  // 0.06768·902 − 41.0823 = 19.964 V, below 19.5 + 0.5
  EXPECT_TRUE(cycle({}).empty());
  EXPECT_TRUE(cycle({}).empty());
  EXPECT_TRUE(has(cycle({}), Invariant::kSupplyWarning));
  status_.bus.missed = 1;
  EXPECT_TRUE(has(cycle({}, {8}), Invariant::kSupplyWarning));  // no reading: the last one holds
  status_.warnings = {"supply 19.96 V near the brown-out voltage"};
  EXPECT_TRUE(cycle({}).empty());
  vcc_ = 903;  // 20.032 V: no warning needed
  status_.warnings.clear();
  for (int k = 0; k < 5; ++k) EXPECT_TRUE(cycle({}).empty());
}

}  // namespace
}  // namespace marsokhod::runner
