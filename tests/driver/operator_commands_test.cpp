// The operator's commands and their ranges, in one place (driver/operator_commands.hpp): every
// refusal names the field and says what is allowed; a settings change replaces only its keys.
#include "driver/operator_commands.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace marsokhod::driver {
namespace {

const Params kParams{};  // max_drive 2.25, spin 1.5, trench 1.0, w = 2.827 rad/s

TEST(OperatorCommands, ConfigurationReplacesOnlyTheKeysGiven) {
  const RuntimeSettings before = runtime_settings_from(kParams);
  SettingsChange change;
  change.load_distribution = LoadDistributionMode::kVariance;
  change.contract_on_turn = false;
  change.speed_scale = 0.5;
  const RuntimeSettings after = change.applied_to(before);
  EXPECT_EQ(after.switches.load_distribution, LoadDistributionMode::kVariance);
  EXPECT_FALSE(after.switches.contract_on_turn);
  EXPECT_EQ(after.speed_scale, 0.5);
  EXPECT_EQ(after.max_drop_v, before.max_drop_v);
  EXPECT_EQ(after.switches.power_management, before.switches.power_management);
  EXPECT_EQ(after.switches.slant_response, before.switches.slant_response);
  EXPECT_EQ(after.switches.axle_placement, before.switches.axle_placement);
  EXPECT_NO_THROW(validate(after));
}

TEST(OperatorCommands, AllOfASettingIsEverySetting) {
  RuntimeSettings s;
  s.max_drop_v = 2.5;
  s.speed_scale = 0.25;
  s.switches = {false, true, false, true, LoadDistributionMode::kSlip};
  EXPECT_EQ(SettingsChange::all_of(s).applied_to(RuntimeSettings{}), s);
  EXPECT_EQ(SettingsChange{}.applied_to(s), s);
}

TEST(OperatorCommands, NumbersOutOfRangeNameTheFieldAndTheRange) {
  EXPECT_FALSE(check_number("v1", 2.25, symmetric_range(2.25, "rad/s")));
  EXPECT_EQ(check_number("v1", 2.3, symmetric_range(2.25, "rad/s"))->message,
            "v1: 2.3 is out of range; allowed \u22122.25..2.25 rad/s");
  EXPECT_EQ(check_number("v1", std::nan(""), symmetric_range(2.25, "rad/s"))->message,
            "v1 is not a finite number");
  EXPECT_EQ(check_number("max_drop_v", 0.0, kMaxDropRange)->message,
            "max_drop_v: 0 is out of range; allowed (0, 10] V");
  EXPECT_EQ(check_number("speed_scale", 1.5, kSpeedScaleRange)->message,
            "speed_scale: 1.5 is out of range; allowed [0, 1]");
}

TEST(OperatorCommands, TargetsAreCheckedAgainstTheParams) {
  mobility::OperatorTargets t;
  EXPECT_FALSE(check_targets(t, kParams));
  t.v3_radps = 1.0;  // max_drift_speed_radps
  EXPECT_FALSE(check_targets(t, kParams));
  t.v3_radps = -1.01;
  EXPECT_EQ(check_targets(t, kParams)->field, "v3");
  t.v3_radps = 0.0;
  t.v4_radps = -1.01;
  EXPECT_EQ(check_targets(t, kParams)->field, "v4");
  t.v4_radps = 0.0;
  t.v7_radps = 2.9;
  EXPECT_EQ(check_targets(t, kParams)->field, "v7");
  t.v7_radps = 0.0;
  t.gait_speed = -1.5;
  EXPECT_EQ(check_targets(t, kParams)->field, "gait_speed");
  t.gait_speed = 0.0;
  t.front_joint_target_rad = kParams.joints.front_max_rad + 0.1;
  const auto joint = check_targets(t, kParams);
  ASSERT_TRUE(joint);
  EXPECT_EQ(joint->field, "front_joint_target");
  EXPECT_NE(joint->message.find("rad (5.3)"), std::string::npos) << joint->message;
  Params fast;
  fast.operator_input.max_drive_speed_radps = 2.5;
  t = {};
  t.v1_radps = 2.3;
  EXPECT_TRUE(check_targets(t, kParams));
  EXPECT_FALSE(check_targets(t, fast));
}

TEST(OperatorCommands, GamepadAxesAndSettingsHaveTheirRanges) {
  mobility::GamepadState pad;
  EXPECT_FALSE(check_gamepad(pad));
  pad.axes[2] = 1.0001;
  EXPECT_EQ(check_gamepad(pad)->field, "axes[2]");
  SettingsChange change;
  change.speed_scale = -0.1;
  EXPECT_EQ(check_settings(change)->field, "speed_scale");
  RuntimeSettings s;
  s.max_drop_v = 10.5;
  EXPECT_THROW(validate(s), std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::driver
