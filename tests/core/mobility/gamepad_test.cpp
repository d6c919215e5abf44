#include "core/mobility/gamepad.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <initializer_list>

#include "core/mobility/elementary_motion.hpp"
#include "mobility_test_support.hpp"

namespace marsokhod::mobility {
namespace {

using testing::expect_invalid_argument;
using testing::kInfinity;
using testing::kNaN;

const OperatorParams kParams;  // dead zone 0.1, v1 2.25, v2 1.5, v4 1.0, joints 0.5 rad/s

GamepadState pad_with_axis(GamepadAxis axis, double value) {
  GamepadState pad;
  pad.axes[axis] = value;
  return pad;
}

GamepadState pad_with_buttons(std::initializer_list<GamepadButton> buttons) {
  GamepadState pad;
  for (const GamepadButton button : buttons) {
    pad.buttons[button] = true;
  }
  return pad;
}

TEST(Gamepad, ReleasedPadAsksForNothing) {
  const OperatorTargets targets = map_gamepad(GamepadState{}, kParams);
  EXPECT_EQ(targets.v1_radps, 0.0);
  EXPECT_EQ(targets.v2_radps, 0.0);
  EXPECT_EQ(targets.v4_radps, 0.0);
  EXPECT_EQ(targets.v6_radps, 0.0);
  EXPECT_EQ(targets.v7_radps, 0.0);
  EXPECT_EQ(targets.gait, Gait::kNone);
  EXPECT_EQ(targets.gait_speed, 0.0);
  EXPECT_FALSE(targets.calibration_mode);
  EXPECT_FALSE(std::signbit(targets.v1_radps));
}

// Dead zone 0.1: 0.05 and 0.0999 read 0; 0.1 reads 0 (continuous); 0.55 → (0.55 − 0.1)/0.9 =
// 0.5; ±1 → ±1.
TEST(Gamepad, DeadZoneIsRescaledToReachFullDeflection) {
  EXPECT_EQ(apply_dead_zone(0.05, 0.1, "x"), 0.0);
  EXPECT_EQ(apply_dead_zone(-0.0999, 0.1, "x"), 0.0);
  EXPECT_EQ(apply_dead_zone(0.1, 0.1, "x"), 0.0);
  EXPECT_DOUBLE_EQ(apply_dead_zone(0.55, 0.1, "x"), 0.5);
  EXPECT_DOUBLE_EQ(apply_dead_zone(-0.55, 0.1, "x"), -0.5);
  EXPECT_EQ(apply_dead_zone(1.0, 0.1, "x"), 1.0);
  EXPECT_EQ(apply_dead_zone(-1.0, 0.1, "x"), -1.0);
  EXPECT_EQ(apply_dead_zone(0.3, 0.0, "x"), 0.3);
}

// Left stick up (axis 1 = −1, W3C: down = +1) drives forward at 2.25 rad/s (0.27 m/s at
// r = 0.12); halfway down (0.55) backs up at 0.5·2.25 = 1.125.
TEST(Gamepad, LeftStickUpDrivesForward) {
  EXPECT_EQ(map_gamepad(pad_with_axis(kLeftStickY, -1.0), kParams).v1_radps, 2.25);
  EXPECT_DOUBLE_EQ(map_gamepad(pad_with_axis(kLeftStickY, 0.55), kParams).v1_radps, -1.125);
}

// Left stick right turns clockwise seen from above: v2 = −1.5, and m2·v2 then runs the left
// wheels forward and the right wheels backward.
TEST(Gamepad, LeftStickRightSpinsClockwise) {
  const OperatorTargets targets = map_gamepad(pad_with_axis(kLeftStickX, 1.0), kParams);
  EXPECT_EQ(targets.v2_radps, -1.5);
  MotorVector w{};
  add_scaled(w, spin_motion(0.45, 0.45, SpinParams{}), targets.v2_radps);
  EXPECT_GT(w[kCenterLeft], 0.0);
  EXPECT_LT(w[kCenterRight], 0.0);
}

// Right stick: up = forward through the gait (s = +1), right = trench with FR forward (v4 = 1).
TEST(Gamepad, RightStickSetsGaitSpeedAndTrench) {
  EXPECT_EQ(map_gamepad(pad_with_axis(kRightStickY, -1.0), kParams).gait_speed, 1.0);
  EXPECT_DOUBLE_EQ(map_gamepad(pad_with_axis(kRightStickY, 0.55), kParams).gait_speed, -0.5);
  EXPECT_EQ(map_gamepad(pad_with_axis(kRightStickX, 1.0), kParams).v4_radps, 1.0);
}

// X and A: the sideways drift m3 at ±max_drift_speed_radps (1.0 rad/s) while held; both cancel,
// and calibration mode silences them like every other velocity.
TEST(Gamepad, XAndADriftSideways) {
  EXPECT_EQ(map_gamepad(pad_with_buttons({kButtonLeft}), kParams).v3_radps, 1.0);
  EXPECT_EQ(map_gamepad(pad_with_buttons({kButtonBottom}), kParams).v3_radps, -1.0);
  EXPECT_EQ(map_gamepad(pad_with_buttons({kButtonLeft, kButtonBottom}), kParams).v3_radps, 0.0);
  OperatorParams slow = kParams;
  slow.max_drift_speed_radps = 0.25;
  EXPECT_EQ(map_gamepad(pad_with_buttons({kButtonBottom}), slow).v3_radps, -0.25);
  const OperatorTargets calibrating = map_gamepad(pad_with_buttons({kSelect}), kParams);
  EXPECT_TRUE(calibrating.calibration_mode);
  EXPECT_EQ(map_gamepad(pad_with_buttons({kButtonLeft}), kParams, calibrating.memory).v3_radps,
            0.0);
  slow.max_drift_speed_radps = -1.0;
  EXPECT_THROW(map_gamepad(GamepadState{}, slow), std::invalid_argument);
}

// d-pad up/right/down/left and Y select the five gaits; the choice stays after release; B clears
// it; two gait buttons at once change nothing.
TEST(Gamepad, GaitButtonsSelectAndLatch) {
  EXPECT_EQ(map_gamepad(pad_with_buttons({kDpadUp}), kParams).gait, Gait::kRolking);
  EXPECT_EQ(map_gamepad(pad_with_buttons({kDpadRight}), kParams).gait, Gait::kFrontWheelWalking);
  EXPECT_EQ(map_gamepad(pad_with_buttons({kDpadDown}), kParams).gait, Gait::kWormLike);
  EXPECT_EQ(map_gamepad(pad_with_buttons({kDpadLeft}), kParams).gait, Gait::kRearWheelWalking);
  EXPECT_EQ(map_gamepad(pad_with_buttons({kButtonTop}), kParams).gait, Gait::kRolkingExtendedBase);
  const OperatorTargets chosen = map_gamepad(pad_with_buttons({kDpadDown}), kParams);
  const OperatorTargets released = map_gamepad(GamepadState{}, kParams, chosen.memory);
  EXPECT_EQ(released.gait, Gait::kWormLike);
  const OperatorTargets both =
      map_gamepad(pad_with_buttons({kDpadUp, kDpadLeft}), kParams, released.memory);
  EXPECT_EQ(both.gait, Gait::kWormLike);
  const OperatorTargets cleared =
      map_gamepad(pad_with_buttons({kButtonRight, kDpadUp}), kParams, both.memory);
  EXPECT_EQ(cleared.gait, Gait::kNone);
}

// Extend front = p6 decreasing (LT → v6 = −0.5), contract front = LB → +0.5; extend rear = p7
// increasing (RT → v7 = +0.5), contract rear = RB → −0.5; both of one joint cancel.
TEST(Gamepad, FrontButtonsBendTheJoints) {
  EXPECT_EQ(map_gamepad(pad_with_buttons({kLeftTrigger}), kParams).v6_radps, -0.5);
  EXPECT_EQ(map_gamepad(pad_with_buttons({kLeftBumper}), kParams).v6_radps, 0.5);
  EXPECT_EQ(map_gamepad(pad_with_buttons({kRightTrigger}), kParams).v7_radps, 0.5);
  EXPECT_EQ(map_gamepad(pad_with_buttons({kRightBumper}), kParams).v7_radps, -0.5);
  const OperatorTargets both = map_gamepad(pad_with_buttons({kLeftBumper, kLeftTrigger}), kParams);
  EXPECT_EQ(both.v6_radps, 0.0);
  EXPECT_TRUE(both.joint_buttons.contract_front);
  EXPECT_TRUE(both.joint_buttons.extend_front);
}

// back/select toggles calibration mode on each press (held = one press). In calibration mode the
// sticks and gaits do nothing; LT + RB give Procedure 4.3's d6 = d7 = −0.08.
TEST(Gamepad, SelectTogglesCalibrationMode) {
  OperatorTargets targets = map_gamepad(pad_with_buttons({kDpadUp}), kParams);
  ASSERT_EQ(targets.gait, Gait::kRolking);
  targets = map_gamepad(pad_with_buttons({kSelect}), kParams, targets.memory);
  EXPECT_TRUE(targets.calibration_mode);
  EXPECT_EQ(targets.gait, Gait::kNone);
  targets = map_gamepad(pad_with_buttons({kSelect}), kParams, targets.memory);
  EXPECT_TRUE(targets.calibration_mode) << "holding the button is one press";
  GamepadState calibrating = pad_with_buttons({kLeftTrigger, kRightBumper, kDpadUp});
  calibrating.axes[kLeftStickY] = -1.0;
  targets = map_gamepad(calibrating, kParams, targets.memory);
  EXPECT_TRUE(targets.calibration_mode);
  EXPECT_EQ(targets.v1_radps, 0.0);
  EXPECT_EQ(targets.v6_radps, 0.0);
  EXPECT_EQ(targets.gait, Gait::kNone);
  const std::array<double, 2> duties = calibration_duties(targets.joint_buttons, kParams);
  EXPECT_EQ(duties[0], -0.08);
  EXPECT_EQ(duties[1], -0.08);
  targets = map_gamepad(pad_with_buttons({kSelect}), kParams, targets.memory);
  EXPECT_FALSE(targets.calibration_mode);
  EXPECT_EQ(targets.gait, Gait::kNone);
}

TEST(Gamepad, RejectsBrokenAxesNamingThem) {
  expect_invalid_argument([] { map_gamepad(pad_with_axis(kLeftStickY, kNaN), kParams); },
                          {"axis 1 (left stick y)"});
  expect_invalid_argument([] { map_gamepad(pad_with_axis(kRightStickX, 1.5), kParams); },
                          {"axis 2 (right stick x)", "[-1, 1]"});
  expect_invalid_argument([] { map_gamepad(pad_with_axis(kRightStickY, -kInfinity), kParams); },
                          {"axis 3 (right stick y)"});
}

TEST(Gamepad, RejectsImpossibleParameters) {
  OperatorParams wide;
  wide.dead_zone = 1.0;
  expect_invalid_argument([&] { map_gamepad(GamepadState{}, wide); }, {"dead_zone"});
  OperatorParams negative;
  negative.max_spin_speed_radps = -1.0;
  expect_invalid_argument([&] { map_gamepad(GamepadState{}, negative); }, {"max_spin_speed_radps"});
  OperatorParams duty;
  duty.calibration_duty = kNaN;
  expect_invalid_argument([&] { validate(duty); }, {"calibration_duty"});
}

}  // namespace
}  // namespace marsokhod::mobility
