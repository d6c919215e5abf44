#include "core/tracking/motor_position.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tracking_test_support.hpp"

namespace marsokhod::tracking {
namespace {

using testing::EmulatedMotorController;
using testing::invalid_argument_message;

constexpr int kPulsesPerRev = 115000;
constexpr double kRadPerCount = 2.0 * std::numbers::pi / kPulsesPerRev;

// Feeds the controller's reading to the tracker after every motion step.
void turn_in_steps(EmulatedMotorController& controller, PositionTracker& tracker,
                   std::int64_t pulses, std::int64_t step) {
  const std::int64_t sign = pulses < 0 ? -1 : 1;
  for (std::int64_t left = pulses * sign; left > 0; left -= step) {
    controller.turn(sign * std::min(left, step));
    tracker.update(controller.reading());
  }
}

TEST(MotorPosition, SameDirectionAcrossWrap) {
  // enc 65500 → 64 forward: (64 − 65500) mod 65536 = 100 pulses, +.
  EXPECT_EQ(position_increment({65500, 0, false}, {64, 0, false}).counts, 100);
  // The same registers with dir = 1 throughout: −100.
  EXPECT_EQ(position_increment({65500, 0, true}, {64, 0, true}).counts, -100);
}

TEST(MotorPosition, DirectionChangeInsideOneCycle) {
  // From enc 100 forward 50 pulses (stp = 150 at the reversal), then back 20 (enc = 170):
  // Δ = ((150 − 100) mod 65536) − ((170 − 150) mod 65536) = 50 − 20 = +30, signed by dir^(k−1) = 0.
  EmulatedMotorController controller(0, 100);
  const EncoderReading before = controller.reading();
  controller.turn(50);
  controller.turn(-20);
  const EncoderReading after = controller.reading();
  EXPECT_EQ(after.stp, 150);
  EXPECT_EQ(after.enc, 170);
  EXPECT_TRUE(after.dir);
  EXPECT_EQ(position_increment(before, after).counts, 30);

  // Back the other way: from dir = 1, back 40 more then forward 10: −(40 − 10) = −30.
  const EncoderReading reversed = controller.reading();
  controller.turn(-40);
  controller.turn(10);
  EXPECT_EQ(position_increment(reversed, controller.reading()).counts, -30);
}

TEST(MotorPosition, DirectionChangeAcrossWrap) {
  // enc 65500, forward 100 (wraps; stp = 64), back 30 (enc = 94): Δ = 100 − 30 = 70.
  EmulatedMotorController controller(0, 65500);
  const EncoderReading before = controller.reading();
  controller.turn(100);
  controller.turn(-30);
  EXPECT_EQ(controller.reading().stp, 64);
  EXPECT_EQ(position_increment(before, controller.reading()).counts, 70);
}

TEST(MotorPosition, ReversalAtEitherEndOfTheCycle) {
  // Reversal right at enc^(k−1) (stp = 100): Δ = 0 − 25 = −25. Right at enc^k: Δ = 25 − 0.
  EXPECT_EQ(position_increment({100, 0, false}, {125, 100, true}).counts, -25);
  EXPECT_EQ(position_increment({100, 0, false}, {125, 125, true}).counts, 25);
}

TEST(MotorPosition, TwoReversalsInsideOneCycleCountTheMidpoint) {
  // Forward 30, back 10, forward 5: truly +25. dir is unchanged, so (3.2)'s first case would count
  // all 45 pulses forward. stp moved to the second change (enc 1040), which shows the hidden pair:
  // the 40 pulses before it count as net zero (true: +20, within [−40, 40]), the 5 after it
  // forward: Δ = 5. For this split (30 forward, 10 back) both are 20 off; the midpoint is never
  // more than 40 off, the printed formula up to 80.
  EmulatedMotorController controller(0, 1000);
  const EncoderReading before = controller.reading();
  controller.turn(30);
  controller.turn(-10);
  controller.turn(5);
  EXPECT_EQ(controller.true_counts(), 25);
  EXPECT_EQ(controller.reading().stp, 1040);
  EXPECT_FALSE(controller.reading().dir);
  const PositionIncrement increment = position_increment(before, controller.reading());
  EXPECT_TRUE(increment.hidden_reversals);
  EXPECT_EQ(increment.counts, 5);
}

TEST(MotorPosition, StickSlipSpringBackCountsNearlyTrue) {
  // A joint that sticks and slips (RELIABILITY.md): the shaft creeps 1 pulse, its coupling springs
  // it back 13 and it runs forward 13 over the same pulses, all in one cycle; truly +1. The
  // printed formula counts 27 forward (an error of 26 = 2·13); the midpoint counts the 14 before
  // the last change as zero and the 13 after it: 13, an error of 12 = 13 − 1.
  EmulatedMotorController controller(7, 2000);
  PositionTracker tracker(0.0, kPulsesPerRev);
  tracker.update(controller.reading());
  controller.turn(1);
  controller.turn(-13);
  controller.turn(13);
  tracker.update(controller.reading());
  EXPECT_EQ(controller.true_counts(), 1);
  EXPECT_EQ(tracker.accumulated_counts(), 13);
  EXPECT_EQ(tracker.hidden_reversal_count(), 1U);
  EXPECT_EQ(tracker.uncertainty_counts(), 14U);  // the 14 pulses before the last change
  // Going on without reversals, the readings count exactly again.
  controller.turn(400);
  tracker.update(controller.reading());
  EXPECT_EQ(tracker.accumulated_counts(), 413);
  EXPECT_EQ(tracker.hidden_reversal_count(), 1U);
}

TEST(MotorPosition, HiddenReversalsWithStpOffTheArcCountTheWholeArc) {
  // stp moved but does not lie on the arc 100 → 130 (a reading the registers cannot explain):
  // no split can be made, the printed formula's first case stands.
  const PositionIncrement increment = position_increment({100, 50, false}, {130, 7, false});
  EXPECT_FALSE(increment.hidden_reversals);
  EXPECT_EQ(increment.counts, 30);
}

TEST(MotorPosition, StaleStpGivesTheMidpointEstimate) {
  // dir flipped but stp = 0 is not on the arc 100 → 130 (eim = 0): the parts would add to
  // 65436 + 130 ≠ 30, so the reversal point is unknown and Δ = 0 (true Δ ∈ [−30, 30]).
  const PositionIncrement increment = position_increment({100, 0, false}, {130, 0, true});
  EXPECT_TRUE(increment.reversal_point_unknown);
  EXPECT_EQ(increment.counts, 0);

  PositionTracker tracker(0.0, kPulsesPerRev);
  tracker.update({100, 0, false});
  tracker.update({130, 0, true});
  EXPECT_EQ(tracker.unknown_reversal_count(), 1U);
  EXPECT_DOUBLE_EQ(tracker.position_rad(), 0.0);
  // p̄ may be off by the whole arc now.
  EXPECT_EQ(tracker.uncertainty_counts(), 30U);
}

// What the registers hid adds up, reading by reading: a hidden pair with a pulses before its
// last change may be off by a (the truth's x − y lies in [−a, a − 2], the midpoint counts 0); a
// reversal with stp off the arc by the whole arc. Readings the registers explain add nothing.
TEST(MotorPosition, TheUncertaintyAddsWhatEachReadingHid) {
  EmulatedMotorController controller(7, 65530);
  PositionTracker tracker(0.0, kPulsesPerRev);
  tracker.update(controller.reading());
  controller.turn(40);  // across the wrap
  tracker.update(controller.reading());
  controller.turn(-12);  // one reversal inside the cycle: exact
  tracker.update(controller.reading());
  EXPECT_EQ(tracker.uncertainty_counts(), 0U);
  EXPECT_EQ(tracker.accumulated_counts(), controller.true_counts());
  controller.turn(-6);  // a hidden pair: 6 + 4 pulses before the last change
  controller.turn(4);
  controller.turn(-9);
  tracker.update(controller.reading());
  EXPECT_EQ(tracker.hidden_reversal_count(), 1U);
  EXPECT_EQ(tracker.uncertainty_counts(), 10U);
  EXPECT_LE(std::abs(tracker.accumulated_counts() - controller.true_counts()), 10);
  controller.set_eim(false);  // the reversal's point goes unrecorded
  controller.turn(5);
  controller.set_eim(true);
  controller.turn(0);
  tracker.update(controller.reading());
  EXPECT_EQ(tracker.unknown_reversal_count(), 1U);
  EXPECT_EQ(tracker.uncertainty_counts(), 15U);
  EXPECT_LE(std::abs(tracker.accumulated_counts() - controller.true_counts()), 15);
}

TEST(MotorPosition, SeveralRevolutionsForwardThenBackAcrossManyWraps) {
  // Joint 7 starts at p̄⁰ = 1.2121 (Remark 3.1). 5 revolutions forward (575000 pulses, enc wraps
  // 9 times) in 800-pulse cycles (≈ 2.7 rad/s at 64 Hz), then 3 back: net +2 revolutions,
  // p̄ = 1.2121 + 2·2π = 13.7785 rad.
  EmulatedMotorController controller(7, 40000);
  PositionTracker tracker(1.2121, kPulsesPerRev);
  tracker.update(controller.reading());
  EXPECT_DOUBLE_EQ(tracker.position_rad(), 1.2121);

  turn_in_steps(controller, tracker, 5 * kPulsesPerRev, 800);
  EXPECT_EQ(tracker.accumulated_counts(), 575000);
  EXPECT_NEAR(tracker.position_rad(), 1.2121 + 10.0 * std::numbers::pi, 1e-9);

  turn_in_steps(controller, tracker, -3 * kPulsesPerRev, 777);
  EXPECT_EQ(tracker.accumulated_counts(), controller.true_counts());
  EXPECT_NEAR(tracker.position_rad(), 1.2121 + 4.0 * std::numbers::pi, 1e-9);
  EXPECT_NEAR(tracker.position_rad(), 13.7785, 1e-4);
}

TEST(MotorPosition, OneReversalInsideEveryCycle) {
  // Each cycle reverses exactly once: from dir 0, +300 then −170 (net +130, ends with dir 1);
  // from dir 1, −250 then +400 (net +150, ends with dir 0); every fifth cycle just runs on 90
  // pulses in the current direction. After 1000 cycles the tracker matches the true count.
  EmulatedMotorController controller(2, 65000);
  PositionTracker tracker(0.0, kPulsesPerRev);
  tracker.update(controller.reading());
  for (int k = 0; k < 1000; ++k) {
    const bool dir = controller.reading().dir;
    if (k % 5 == 4) {
      controller.turn(dir ? -90 : 90);
    } else if (!dir) {
      controller.turn(300);
      controller.turn(-170);
    } else {
      controller.turn(-250);
      controller.turn(400);
    }
    tracker.update(controller.reading());
    ASSERT_EQ(tracker.accumulated_counts(), controller.true_counts()) << "cycle " << k;
  }
  EXPECT_EQ(tracker.unknown_reversal_count(), 0U);
  EXPECT_GT(controller.true_counts(), 65536);  // the run wrapped enc more than once
  EXPECT_DOUBLE_EQ(tracker.position_rad(),
                   kRadPerCount * static_cast<double>(controller.true_counts()));
}

TEST(MotorPosition, RejectsInvalidParameters) {
  EXPECT_DOUBLE_EQ(encoder_rad_per_count(115000), 2.0 * std::numbers::pi / 115000.0);
  EXPECT_THAT(invalid_argument_message([] { PositionTracker(0.0, 0); }),
              ::testing::HasSubstr("motors.encoder_pulses_per_rev"));
  EXPECT_THAT(invalid_argument_message([] { PositionTracker(std::nan(""), 115000); }),
              ::testing::HasSubstr("motors.initial_position_rad"));
}

}  // namespace
}  // namespace marsokhod::tracking
