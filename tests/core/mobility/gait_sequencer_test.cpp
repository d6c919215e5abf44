#include "core/mobility/gait_sequencer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <random>
#include <vector>

#include "core/control/motion_model.hpp"
#include "mobility_test_support.hpp"

namespace marsokhod::mobility {
namespace {

using testing::expect_invalid_argument;
using testing::kNaN;

constexpr double kPeriodS = 0.0156;              // h, 64 Hz
constexpr double kFullSpeedRadps = 0.5 * 2.827;  // C = max_joint_speed_fraction·w = 1.4135
constexpr std::array<Gait, 5> kGaits{Gait::kRolking, Gait::kFrontWheelWalking,
                                     Gait::kRearWheelWalking, Gait::kWormLike,
                                     Gait::kRolkingExtendedBase};

// The joints as the model of Lemma 4.15: each cycle applies (4.12)/(4.13) with the sequencer's c.
// Starts contracted, (p6, p7) = (−1.2121, 1.2121), at rest.
struct Rover {
  GaitSequencer sequencer{GeometryParams{}, JointParams{}, GaitParams{}, MotorParams{}};
  control::MotionState front{-1.2121, 0.0};
  control::MotionState rear{1.2121, 0.0};
  GaitOutput last;
  std::optional<JointBounds> front_bounds;  // the behaviours' bounds (6.4), none: (5.3) alone
  std::optional<JointBounds> rear_bounds;
  double uphill = 0.0;  // GaitInput::uphill

  GaitOutput cycle(Gait gait, double speed, DrivingIntent intent = DrivingIntent::kForward) {
    last = sequencer.update({gait, speed, intent, front, rear, kPeriodS, std::nullopt,
                             std::nullopt, front_bounds, rear_bounds, uphill});
    if (last.active) {
      const control::ControlParams model{0.4, kFullSpeedRadps, kPeriodS};
      front = control::step(front, last.front_control_radps, model);
      rear = control::step(rear, last.rear_control_radps, model);
    }
    return last;
  }
};

void expect_within_bounds(const Rover& rover) {
  const JointParams joints;
  ASSERT_GE(rover.front.position, joints.front_min_rad);
  ASSERT_LE(rover.front.position, joints.front_max_rad);
  ASSERT_GE(rover.rear.position, joints.rear_min_rad);
  ASSERT_LE(rover.rear.position, joints.rear_max_rad);
}

// Runs until `changes` state changes happened (or max_steps) and returns the visited indices.
// At every change the joints were at the left state's targets, within 0.05 rad and stopped.
std::vector<std::size_t> run_states(Rover& rover, Gait gait, double speed, DrivingIntent intent,
                                    std::size_t changes, std::size_t max_steps = 40000) {
  std::vector<std::size_t> visited{rover.cycle(gait, speed, intent).state_index};
  for (std::size_t k = 0; k < max_steps && visited.size() <= changes; ++k) {
    const control::MotionState front = rover.front;
    const control::MotionState rear = rover.rear;
    const GaitOutput before = rover.last;
    const GaitOutput now = rover.cycle(gait, speed, intent);
    expect_within_bounds(rover);
    if (now.state_index != visited.back()) {
      EXPECT_LE(std::abs(front.position - before.front_target_rad), 0.05);
      EXPECT_LE(std::abs(rear.position - before.rear_target_rad), 0.05);
      EXPECT_LE(std::abs(front.velocity), GaitSequencer::kStoppedSpeedRadps);
      EXPECT_LE(std::abs(rear.velocity), GaitSequencer::kStoppedSpeedRadps);
      visited.push_back(now.state_index);
    }
  }
  return visited;
}

// s = 1: every gait, both driving intents, cycles 0 → 1 → 0 → 1 → 0 → 1 on the model, each state
// reached and stopped at before the next starts, the joints inside (5.3) throughout. The joints
// start half bent, so that no state is reached in the first cycle.
TEST(GaitSequencer, EveryGaitCyclesThroughItsStatesInOrder) {
  for (const Gait gait : kGaits) {
    for (const DrivingIntent intent : {DrivingIntent::kForward, DrivingIntent::kBackward}) {
      Rover rover;
      rover.front = {-1.7, 0.0};
      rover.rear = {1.7, 0.0};
      const std::vector<std::size_t> visited = run_states(rover, gait, 1.0, intent, 5);
      EXPECT_EQ(visited, (std::vector<std::size_t>{0, 1, 0, 1, 0, 1}))
          << gait_name(gait) << " intent " << intent_value(intent);
    }
  }
}

// s = −1 on every gait and intent: the cycle backward, starting toward the last state. While
// approaching state k backward the transition k → k+1 is undone, with that transition's fixed ρ;
// forward, approaching k uses k's own rule. (Every SPEC gait has two states, so backward and
// forward alternate alike; the start and the ρ tell them apart.)
TEST(GaitSequencer, EveryGaitRunsBackwardWithTheUndoneTransitionsRule) {
  for (const Gait gait : kGaits) {
    for (const DrivingIntent intent : {DrivingIntent::kForward, DrivingIntent::kBackward}) {
      for (const double speed : {1.0, -1.0}) {
        Rover rover;
        rover.front = {-1.7, 0.0};
        rover.rear = {1.7, 0.0};
        std::size_t changes = 0;
        std::size_t index = rover.cycle(gait, speed, intent).state_index;
        EXPECT_EQ(index, speed > 0 ? 0u : 1u) << gait_name(gait);
        for (int k = 0; k < 40000 && changes < 5; ++k) {
          const GaitOutput output = rover.cycle(gait, speed, intent);
          const std::size_t next = output.state_index;
          changes += next != index ? 1 : 0;
          ASSERT_TRUE(next == index || next == 1 - index);  // two states per cycle
          index = next;
          const std::size_t rule_state = speed > 0 ? index : (index + 1) % 2;
          const AxleRule rule = gait_state(gait, rule_state, intent).rule;
          if (rule.kind == AxleRule::Kind::kFixed) {
            ASSERT_EQ(output.factors.front, rule.fixed.front) << gait_name(gait) << " " << speed;
            ASSERT_EQ(output.factors.rear, rule.fixed.rear) << gait_name(gait) << " " << speed;
          }
        }
        EXPECT_EQ(changes, 5u) << gait_name(gait) << " " << speed;
      }
    }
  }
}

// s = −1 runs the cycle backward: it starts toward the last state and undoes each transition with
// that transition's own ρ. From (C,C), front-wheel walking forward finds (C,H) reached at once and
// approaches (E,H) with ρf = 1 (the front steps out); backward it approaches (E,H) first, with
// ρf = 0 (E → C undone: the body is pushed back).
TEST(GaitSequencer, NegativeSpeedRunsTheCycleInReverse) {
  Rover backward;
  EXPECT_EQ(run_states(backward, Gait::kFrontWheelWalking, -1.0, DrivingIntent::kForward, 4),
            (std::vector<std::size_t>{1, 0, 1, 0, 1}));
  Rover forward;
  const GaitOutput out = forward.cycle(Gait::kFrontWheelWalking, 1.0);
  EXPECT_EQ(out.state_index, 1u);
  EXPECT_EQ(out.front_target_rad, -2.55);
  EXPECT_EQ(out.factors.front, 1.0);
  Rover reverse;
  const GaitOutput back = reverse.cycle(Gait::kFrontWheelWalking, -1.0);
  EXPECT_EQ(back.state_index, 1u);
  EXPECT_EQ(back.front_target_rad, -2.55);
  EXPECT_EQ(back.factors.front, 0.0);
}

// Reversing mid-transition turns back to the state just left, with the same ρ rule (the same
// transition, undone). Rolking from (E,C) toward (C,E) uses the ε-formula; turned back toward
// (E,C) it still does; from (E,C) backward the next target is (C,E) with ρf = ρr = 1.
TEST(GaitSequencer, ReversingMidTransitionReturnsToTheStateLeft) {
  Rover rover;
  run_states(rover, Gait::kRolking, 1.0, DrivingIntent::kForward, 2);  // 0 → 1 → 0
  ASSERT_EQ(rover.last.state_index, 0u);
  for (int k = 0; k < 60; ++k) {
    rover.cycle(Gait::kRolking, 1.0);
  }
  const GaitOutput ahead = rover.last;
  const GaitOutput back = rover.cycle(Gait::kRolking, -1.0);
  EXPECT_EQ(back.state_index, 1u);
  EXPECT_EQ(back.front_target_rad, -2.55);
  EXPECT_EQ(back.rear_target_rad, 1.2121);
  EXPECT_NEAR(back.factors.front + back.factors.rear, ahead.factors.front + ahead.factors.rear,
              0.05);
  EXPECT_EQ(run_states(rover, Gait::kRolking, -1.0, DrivingIntent::kForward, 1),
            (std::vector<std::size_t>{1, 0}));
  EXPECT_EQ(rover.last.factors.front, 1.0);
  EXPECT_EQ(rover.last.factors.rear, 1.0);
  EXPECT_EQ(rover.last.front_target_rad, -1.2121);
  EXPECT_EQ(rover.last.rear_target_rad, 2.55);
}

// s = 0 holds: mid-transition the joints come to rest and stay, the state and targets stay; s = 1
// then finishes the transition.
TEST(GaitSequencer, ZeroSpeedHolds) {
  Rover rover;
  for (int k = 0; k < 10000 && std::abs(rover.front.velocity) < 0.5; ++k) {
    rover.cycle(Gait::kWormLike, 1.0);  // accelerating from (C,C) toward (E,E)
  }
  ASSERT_GE(std::abs(rover.front.velocity), 0.5);
  const GaitOutput moving = rover.last;
  for (int k = 0; k < 3000; ++k) {
    const GaitOutput held = rover.cycle(Gait::kWormLike, 0.0);
    ASSERT_EQ(held.state_index, moving.state_index);
    ASSERT_EQ(held.front_target_rad, moving.front_target_rad);
    ASSERT_EQ(held.rear_target_rad, moving.rear_target_rad);
    expect_within_bounds(rover);
  }
  EXPECT_LT(std::abs(rover.front.velocity), 1e-9);
  EXPECT_LT(std::abs(rover.rear.velocity), 1e-9);
  const double resting = rover.front.position;
  rover.cycle(Gait::kWormLike, 0.0);
  EXPECT_NEAR(rover.front.position, resting, 1e-12);
  EXPECT_GT(std::abs(rover.front.position - moving.front_target_rad), 0.1);
  const std::vector<std::size_t> visited =
      run_states(rover, Gait::kWormLike, 1.0, DrivingIntent::kForward, 1);
  EXPECT_EQ(visited, (std::vector<std::size_t>{1, 0}));
}

// "The motors are stopped" is judged on the measured joint velocity when the driver has one: the
// commanded ŵ (the velocity state) can stay at 0.04 rad/s while the motor stands in its dead zone.
TEST(GaitSequencer, StoppedIsTheMeasuredJointVelocity) {
  const auto next_state = [](double state_radps, std::optional<double> measured_radps) {
    GaitSequencer sequencer{GeometryParams{}, JointParams{}, GaitParams{}, MotorParams{}};
    const GaitOutput first = sequencer.update(
        {Gait::kRolking, 1.0, DrivingIntent::kForward, {-1.7, 0.0}, {1.7, 0.0}, kPeriodS});
    GaitInput at_target{Gait::kRolking,
                        1.0,
                        DrivingIntent::kForward,
                        {first.front_target_rad, state_radps},
                        {first.rear_target_rad, state_radps},
                        kPeriodS,
                        measured_radps,
                        measured_radps};
    return sequencer.update(at_target).state_index != first.state_index;
  };
  EXPECT_TRUE(next_state(0.04, 0.0));   // standing in the dead zone: stopped
  EXPECT_FALSE(next_state(0.0, 0.04));  // still moving although the command reached 0
  EXPECT_FALSE(next_state(0.04, std::nullopt));  // no measurement: the velocity state decides
  EXPECT_TRUE(next_state(0.0, std::nullopt));
}

// |s| scales C: at s = 0.5 the control stays within 0.5·C and a transition takes longer.
TEST(GaitSequencer, StickDeflectionScalesTheJointSpeed) {
  const auto first_change = [](double speed) {
    Rover rover;
    rover.cycle(Gait::kRolking, speed);
    double largest = 0.0;
    for (int k = 1; k < 40000; ++k) {
      const GaitOutput output = rover.cycle(Gait::kRolking, speed);
      largest = std::max(
          {largest, std::abs(output.front_control_radps), std::abs(output.rear_control_radps)});
      if (output.state_index == 1) {
        return std::pair{k, largest};
      }
    }
    return std::pair{-1, largest};
  };
  const auto [full_steps, full_control] = first_change(1.0);
  const auto [half_steps, half_control] = first_change(0.5);
  ASSERT_GT(full_steps, 0);
  EXPECT_GT(half_steps, full_steps);
  EXPECT_LE(half_control, 0.5 * kFullSpeedRadps + 1e-12);
  EXPECT_LE(full_control, kFullSpeedRadps + 1e-12);
}

// Dropping s to 0.02 while a joint moves fast toward a bound: the (4.16) clip at the full C still
// stops it inside (5.3).
TEST(GaitSequencer, SlowingDownMidStrokeKeepsTheBounds) {
  Rover rover;
  for (int k = 0; k < 10000 && std::abs(rover.front.velocity) < 0.6; ++k) {
    rover.cycle(Gait::kWormLike, 1.0);
  }
  ASSERT_GE(std::abs(rover.front.velocity), 0.6);
  for (int k = 0; k < 10000; ++k) {
    rover.cycle(Gait::kWormLike, 0.02);
    expect_within_bounds(rover);
  }
}

// A new driving intent takes effect at the next state change (then the table is mirrored), and a
// held joint keeps the position measured when the gait started (or when the intent changed).
TEST(GaitSequencer, IntentChangesAtTheNextState) {
  Rover rover;
  rover.front = {-1.7, 0.0};
  rover.rear = {1.9, 0.0};
  const GaitOutput start = rover.cycle(Gait::kFrontWheelWalking, 1.0, DrivingIntent::kForward);
  ASSERT_EQ(start.state_index, 0u);
  EXPECT_EQ(start.front_target_rad, -1.2121);  // (C,H)
  EXPECT_EQ(start.rear_target_rad, 1.9);
  EXPECT_EQ(start.factors.front, 0.0);
  const GaitOutput flipped = rover.cycle(Gait::kFrontWheelWalking, 1.0, DrivingIntent::kBackward);
  EXPECT_EQ(flipped.state_index, 0u);
  EXPECT_EQ(flipped.front_target_rad, start.front_target_rad);
  EXPECT_EQ(flipped.rear_target_rad, start.rear_target_rad);
  for (int k = 0; k < 40000 && rover.last.state_index == 0; ++k) {
    rover.cycle(Gait::kFrontWheelWalking, 1.0, DrivingIntent::kBackward);
  }
  // Mirrored state 1 is (H,E): the front is now held where it stopped, at C; the rear steps out
  // with the mirrored ρf = 1, i.e. ρr = 1 (backward).
  ASSERT_EQ(rover.last.state_index, 1u);
  EXPECT_NEAR(rover.last.front_target_rad, -1.2121, 0.05);
  EXPECT_EQ(rover.last.rear_target_rad, 2.55);
  EXPECT_EQ(rover.last.factors.rear, 1.0);
  EXPECT_EQ(rover.last.factors.front, 0.0);
}

// Kinds of gait changes: a new gait restarts at state 0; none deactivates.
TEST(GaitSequencer, SelectingAGaitRestartsItAndNoneStops) {
  Rover rover;
  run_states(rover, Gait::kRolking, 1.0, DrivingIntent::kForward, 1);
  ASSERT_EQ(rover.last.state_index, 1u);
  EXPECT_EQ(rover.cycle(Gait::kWormLike, 1.0).state_index, 0u);
  EXPECT_EQ(rover.sequencer.gait(), Gait::kWormLike);
  const GaitOutput off = rover.cycle(Gait::kNone, 1.0);
  EXPECT_FALSE(off.active);
  EXPECT_EQ(off.front_control_radps, 0.0);
  EXPECT_EQ(rover.sequencer.gait(), Gait::kNone);
}

// Random measured states (inside and up to 0.5 rad outside (5.3)), gaits, intents and speeds:
// every target lies in (5.3), every control in [−C, C], every output finite.
TEST(GaitSequencer, TargetsNeverLeaveTheJointBounds) {
  const JointParams joints;
  GaitSequencer sequencer{GeometryParams{}, joints, GaitParams{}, MotorParams{}};
  std::mt19937 random(57);
  std::uniform_real_distribution<double> front_position(-3.05, -0.71);
  std::uniform_real_distribution<double> rear_position(0.71, 3.05);
  std::uniform_real_distribution<double> velocity(-kFullSpeedRadps, kFullSpeedRadps);
  std::uniform_real_distribution<double> speed(-1.0, 1.0);
  std::uniform_int_distribution<int> choice(0, 5);
  for (int k = 0; k < 20000; ++k) {
    const Gait gait = k % 50 == 0 ? static_cast<Gait>(choice(random)) : sequencer.gait();
    const double s = k % 7 == 0 ? 0.0 : speed(random);
    const DrivingIntent intent =
        choice(random) < 3 ? DrivingIntent::kForward : DrivingIntent::kBackward;
    const GaitOutput output = sequencer.update({gait,
                                                s,
                                                intent,
                                                {front_position(random), velocity(random)},
                                                {rear_position(random), velocity(random)},
                                                kPeriodS});
    if (!output.active) {
      continue;
    }
    ASSERT_GE(output.front_target_rad, joints.front_min_rad);
    ASSERT_LE(output.front_target_rad, joints.front_max_rad);
    ASSERT_GE(output.rear_target_rad, joints.rear_min_rad);
    ASSERT_LE(output.rear_target_rad, joints.rear_max_rad);
    ASSERT_LE(std::abs(output.front_control_radps), kFullSpeedRadps + 1e-12);
    ASSERT_LE(std::abs(output.rear_control_radps), kFullSpeedRadps + 1e-12);
    ASSERT_TRUE(std::isfinite(output.front_command_radps + output.rear_command_radps +
                              output.factors.front + output.factors.rear));
  }
}

// The command is the model's next velocity (4.13): v·e^(−hμ) + c·(1 − e^(−hμ)).
TEST(GaitSequencer, CommandIsTheNextModelVelocity) {
  Rover rover;
  rover.front = {-1.5, -0.3};
  const GaitOutput output = rover.cycle(Gait::kRolking, 1.0);
  const double decay = std::exp(-kPeriodS * 0.4);
  EXPECT_NEAR(output.front_command_radps, -0.3 * decay + output.front_control_radps * (1.0 - decay),
              1e-15);
  EXPECT_NEAR(output.front_command_radps, rover.front.velocity, 1e-15);
}

// γ(20°) of (6.4): acos(−(a·s + √((a²s + b²)·sin²σ))/b) with s = −1 + sin²20°, a = 0.145,
// b = 0.413: the rear joint's slant bound p7_min on a 20° ascent.
constexpr double kSlantBound20DegRad = 1.5836473;

// On a 20° ascent the slant response bounds the rear joint to [γ(σ), 2.55]. The gaits that
// contract the rear joint to C = 1.2121 end that stroke at γ(σ) instead, reach every state and
// go round (without the clip the contracted target would lie below the bound and never be
// reached inside it); the rear joint never leaves the bound.
TEST(GaitSequencer, SlantBoundClipsTheStrokeAndTheGaitGoesRound) {
  for (const Gait gait : {Gait::kRolking, Gait::kRearWheelWalking, Gait::kWormLike}) {
    SCOPED_TRACE(static_cast<int>(gait));
    Rover rover;
    rover.front = {-1.7, 0.0};
    rover.rear = {1.9, 0.0};
    rover.rear_bounds = JointBounds{kSlantBound20DegRad, 2.55};
    double lowest_target = 10.0;
    double lowest_rear = 10.0;
    std::size_t changes = 0;
    std::size_t state = rover.cycle(gait, 1.0).state_index;
    for (int k = 0; k < 40000 && changes < 5; ++k) {
      const GaitOutput output = rover.cycle(gait, 1.0);
      lowest_target = std::min(lowest_target, output.rear_target_rad);
      lowest_rear = std::min(lowest_rear, rover.rear.position);
      if (output.state_index != state) ++changes;
      state = output.state_index;
    }
    EXPECT_EQ(changes, 5u);
    EXPECT_NEAR(lowest_target, kSlantBound20DegRad, 1e-12);
    EXPECT_GE(lowest_rear, kSlantBound20DegRad - 1e-5);
  }
}

// Front-wheel walking holds the rear joint where it stood when the gait started, here C =
// 1.2121, below the slope's bound γ(20°): its target is the bound, (4.16)'s lower term pulls it
// up at +C (full speed: "back inside as fast as possible"), and the first state is reached once
// it is there and stopped; from then on it stays inside while the front walks.
TEST(GaitSequencer, HeldJointIsPulledBackInsideTheSlantBound) {
  Rover rover;
  rover.rear_bounds = JointBounds{kSlantBound20DegRad, 2.55};
  const GaitOutput first = rover.cycle(Gait::kFrontWheelWalking, 1.0);
  EXPECT_NEAR(first.rear_target_rad, kSlantBound20DegRad, 1e-12);
  EXPECT_NEAR(first.rear_control_radps, kFullSpeedRadps, 1e-12);
  int k = 0;
  while (k < 2000 && rover.last.state_index == 0) {
    rover.cycle(Gait::kFrontWheelWalking, 1.0);
    ++k;
  }
  ASSERT_EQ(rover.last.state_index, 1u);
  // 0.37 rad at up to C with μ = 0.4 /s: about 2 s up and 1 s of braking, well under 5 s.
  EXPECT_LT(k * kPeriodS, 5.0);
  EXPECT_NEAR(rover.rear.position, kSlantBound20DegRad, 0.05);
  std::size_t changes = 0;
  for (std::size_t state = 1; k < 40000 && changes < 3; ++k) {
    rover.cycle(Gait::kFrontWheelWalking, 1.0);
    ASSERT_GE(rover.rear.position, kSlantBound20DegRad - 1e-5);
    if (rover.last.state_index != state) ++changes;
    state = rover.last.state_index;
  }
  EXPECT_EQ(changes, 3u);
}

// A slope so steep that the bound leaves the rear stroke 0.03 rad (γ(σ) = 2.52 at σ ≈ 63.4°, E =
// 2.55): rear-wheel walking reaches (H,C) = (H, 2.52) and does not start the transition to
// (H,E) = (H, 2.55), which would be reached at once; it holds there, saying so. Widened bounds
// let it go on by itself.
TEST(GaitSequencer, NoRoomInsideTheBoundsHoldsAtTheReachedState) {
  Rover rover;
  rover.front = {-1.5, 0.0};
  rover.rear = {2.52, 0.0};
  rover.rear_bounds = JointBounds{2.52, 2.55};
  for (int k = 0; k < 1000; ++k) {
    const GaitOutput output = rover.cycle(Gait::kRearWheelWalking, 1.0);
    ASSERT_EQ(output.state_index, 0u);
    ASSERT_TRUE(output.held_by_bounds);
    ASSERT_NEAR(output.rear_target_rad, 2.52, 1e-12);
  }
  rover.rear_bounds = JointBounds{2.3, 2.55};
  for (int k = 0; k < 2000 && rover.last.state_index == 0; ++k) {
    rover.cycle(Gait::kRearWheelWalking, 1.0);
  }
  EXPECT_EQ(rover.last.state_index, 1u);
  EXPECT_FALSE(rover.last.held_by_bounds);
  EXPECT_EQ(rover.last.rear_target_rad, 2.55);
}

// On a slope the ε-formula's states take the joints' mismatch uphill (uphill_axle_factors); the
// states with a fixed ρ keep it. Rolking's first stroke from contracted joints, (C,C) → (C,E),
// moves the rear joint alone (yf = 0, yr > 0): the printed formula gives (½, ½), the rear anchor
// rolled back by yr/2; forward uphill ρr = 0 (q = min(0, yr) = 0: the rear axle stands, the front
// and centre advance by yr), backward uphill ρr = 1 (q = yr: the rear axle goes back, uphill).
// ρf stays ½, the nearest to ε: the front joint does not move. The next stroke, to (E,C), has
// ρ = (1, 1) on any ground, and front-wheel walking's fixed ρ are the flat ground's.
TEST(GaitSequencer, OnASlopeTheEpsilonStatesTakeTheMismatchUphill) {
  for (const double uphill : {0.0, 1.0, -1.0}) {
    SCOPED_TRACE(uphill);
    Rover rover;
    rover.uphill = uphill;
    for (int k = 0; k < 30; ++k) rover.cycle(Gait::kRolking, 1.0);
    ASSERT_EQ(rover.last.state_index, 0u);
    ASSERT_GT(rover.rear.velocity, 0.1);
    ASSERT_EQ(rover.front.velocity, 0.0);
    EXPECT_EQ(rover.last.factors.front, 0.5);
    EXPECT_EQ(rover.last.factors.rear, uphill == 0.0 ? 0.5 : (uphill > 0.0 ? 0.0 : 1.0));
    run_states(rover, Gait::kRolking, 1.0, DrivingIntent::kForward, 1);
    ASSERT_EQ(rover.last.state_index, 1u);
    EXPECT_EQ(rover.last.factors.front, 1.0);
    EXPECT_EQ(rover.last.factors.rear, 1.0);
    Rover sloped, flat;
    sloped.uphill = uphill;
    for (int k = 0; k < 300; ++k) {
      const AxleFactors on_slope = sloped.cycle(Gait::kFrontWheelWalking, 1.0).factors;
      const AxleFactors on_flat = flat.cycle(Gait::kFrontWheelWalking, 1.0).factors;
      ASSERT_EQ(on_slope.front, on_flat.front) << k;
      ASSERT_EQ(on_slope.rear, on_flat.rear) << k;
    }
  }
}

TEST(GaitSequencer, RejectsInvalidInputsNamingThem) {
  GaitSequencer sequencer{GeometryParams{}, JointParams{}, GaitParams{}, MotorParams{}};
  GaitInput input{Gait::kRolking, 0.5, DrivingIntent::kForward, {-1.5, 0.0}, {1.5, 0.0}, kPeriodS};
  input.front_joint.position = kNaN;
  expect_invalid_argument([&] { sequencer.update(input); }, {"front_joint.position (p6)"});
  input.front_joint.position = -1.5;
  input.rear_joint.velocity = kNaN;
  expect_invalid_argument([&] { sequencer.update(input); }, {"rear_joint.velocity (w7)"});
  input.rear_joint.velocity = 0.0;
  input.gait_speed = 1.5;
  expect_invalid_argument([&] { sequencer.update(input); }, {"gait_speed"});
  input.gait_speed = 0.5;
  input.period_s = 0.0;
  expect_invalid_argument([&] { sequencer.update(input); }, {"period_s"});
  input.period_s = kPeriodS;
  input.rear_bounds = JointBounds{2.0, 1.9};
  expect_invalid_argument([&] { sequencer.update(input); }, {"rear_bounds.min_rad (p7_min)"});
  input.rear_bounds.reset();
  input.front_bounds = JointBounds{-2.55, kNaN};
  expect_invalid_argument([&] { sequencer.update(input); }, {"front_bounds.max_rad (p6_max)"});
  input.front_bounds.reset();
  input.uphill = 0.5;
  expect_invalid_argument([&] { sequencer.update(input); }, {"uphill", "0, +1 or -1"});
  MotorParams stopped;
  stopped.max_no_load_speed_radps = 0.0;
  expect_invalid_argument(
      [&] { GaitSequencer(GeometryParams{}, JointParams{}, GaitParams{}, stopped); },
      {"max_no_load_speed_radps"});
}

}  // namespace
}  // namespace marsokhod::mobility
