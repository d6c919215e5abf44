// The commands' one JSON codec (command_json.hpp), as the recordings and scenario files use it:
// every field survives encode → text → decode; every refusal names the field by its path; a
// recording is read as it was written, out-of-range values included (the driver judges them).
#include "link/command_json.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "link/json_fields.hpp"

namespace marsokhod::link {
namespace {

using nlohmann::json;

driver::OperatorInput through_text(const driver::OperatorInput& input) {
  return operator_input_from_json(json::parse(operator_input_json(input).dump()));
}

// The field of the FieldError that reading `text` as an operator input throws.
std::string input_error(const std::string& text) {
  try {
    operator_input_from_json(json::parse(text));
  } catch (const FieldError& e) {
    EXPECT_NE(std::string(e.what()).find(e.field()), std::string::npos) << e.what();
    return e.field();
  }
  ADD_FAILURE() << "accepted: " << text;
  return "";
}

std::string runtime_error_field(const std::string& text) {
  try {
    runtime_settings_from_json(json::parse(text), driver::RuntimeSettings{});
  } catch (const FieldError& e) {
    EXPECT_NE(std::string(e.what()).find(e.field()), std::string::npos) << e.what();
    return e.field();
  }
  ADD_FAILURE() << "accepted: " << text;
  return "";
}

TEST(CommandJson, EveryFieldOfAnOperatorInputRoundTrips) {
  driver::OperatorInput targets;
  mobility::OperatorTargets& t = targets.targets.emplace();
  t.v1_radps = 2.25;
  t.v2_radps = -1.5;
  t.v3_radps = -0.75;
  t.v4_radps = 0.125;
  t.v6_radps = -2.827;
  t.v7_radps = 1e-7;
  t.gait = mobility::Gait::kRearWheelWalking;
  t.gait_speed = -0.3;
  t.calibration_mode = true;
  t.joint_buttons = {true, false, false, true};
  t.front_joint_target_rad = -1.61;
  t.rear_joint_target_rad = 2.21;
  targets.stop = true;
  targets.stop_reason = "client 3 pressed STOP; client 1 lost control";
  targets.clear_faults = true;
  EXPECT_EQ(through_text(targets), targets);

  driver::OperatorInput pad;
  pad.gamepad.emplace();
  pad.gamepad->axes = {0.25, -1.0, 1.0, -0.125};
  pad.gamepad->buttons[mobility::kSelect] = true;
  pad.gamepad->buttons[mobility::kHome] = true;
  EXPECT_EQ(through_text(pad), pad);
  EXPECT_EQ(through_text(driver::OperatorInput{}), driver::OperatorInput{});
  for (const mobility::Gait gait : mobility::kAllGaits) {
    targets.targets->gait = gait;
    EXPECT_EQ(through_text(targets), targets);
  }
}

TEST(CommandJson, EveryRuntimeSettingRoundTrips) {
  driver::RuntimeSettings s;
  s.max_drop_v = 0.75;
  s.speed_scale = 0.5;
  s.switches = {false, true, false, true, LoadDistributionMode::kVariance};
  s.supply = SupplyKind::kTether;
  const json text = json::parse(runtime_settings_json(s).dump());
  EXPECT_EQ(text.at("supply"), "tether");
  EXPECT_EQ(runtime_settings_from_json(text, driver::RuntimeSettings{}), s);
  for (const auto mode :
       {LoadDistributionMode::kOff, LoadDistributionMode::kVariance, LoadDistributionMode::kSlip}) {
    s.switches.load_distribution = mode;
    EXPECT_EQ(runtime_settings_from_json(runtime_settings_json(s), driver::RuntimeSettings{}), s);
  }
}

TEST(CommandJson, ASettingsChangeCarriesOnlyItsKeys) {
  driver::SettingsChange change;
  change.slant_response = false;
  change.max_drop_v = 2.0;
  json object = json::object();
  write_settings_change(change, object);
  EXPECT_EQ(object, json::parse(R"({"max_drop_v":2.0,"behaviours":{"slant_response":false}})"));
  EXPECT_EQ(read_settings_change(object, {"", "configure", nullptr}), change);
  driver::RuntimeSettings base;
  base.speed_scale = 0.25;
  const driver::RuntimeSettings after = runtime_settings_from_json(object, base);
  EXPECT_EQ(after, change.applied_to(base));
  EXPECT_EQ(after.speed_scale, 0.25);
}

TEST(CommandJson, TheConsoleWritesOnlyItsOwnTargetKeys) {
  mobility::OperatorTargets t;
  t.front_joint_target_rad = -1.5;
  t.joint_buttons.extend_rear = true;
  json object = json::object();
  write_targets(t, TargetKeys::kConsole, object);
  for (const auto& [key, value] : object.items()) {
    const auto keys = target_keys(TargetKeys::kConsole);
    EXPECT_NE(std::find(keys.begin(), keys.end(), key), keys.end()) << key;
  }
  EXPECT_EQ(object.size(), target_keys(TargetKeys::kConsole).size());
}

TEST(CommandJson, ARecordingIsReadAsItWasWrittenOutOfRangeValuesIncluded) {
  // The driver refused this input live (|v1| > 2.25); replay must hand it over again.
  const driver::OperatorInput in =
      operator_input_from_json(json::parse(R"({"targets":{"v1":99,"gait_speed":-4}})"));
  EXPECT_EQ(in.targets->v1_radps, 99.0);
  EXPECT_EQ(in.targets->gait_speed, -4.0);
  EXPECT_EQ(in.targets->gait, mobility::Gait::kNone);
}

TEST(CommandJson, BadInputIsRefusedNamingTheField) {
  EXPECT_EQ(input_error(R"({"targets":{"v1":"fast"}})"), "targets.v1");
  EXPECT_EQ(input_error(R"({"targets":{"gait":"hop"}})"), "targets.gait");
  EXPECT_EQ(input_error(R"({"targets":{"v5":0}})"), "targets.v5");  // m5 is reserved
  EXPECT_EQ(input_error(R"({"targets":{"joint_buttons":[true]}})"), "targets.joint_buttons");
  EXPECT_EQ(input_error(R"({"targets":{"joint_buttons":[1,0,0,0]}})"), "targets.joint_buttons[0]");
  EXPECT_EQ(input_error(R"({"targets":{"front_joint_target":null}})"),
            "targets.front_joint_target");
  EXPECT_EQ(input_error(R"({"gamepad":{"axes":[0,0,0,0]}})"), "gamepad.buttons");
  EXPECT_EQ(input_error(R"({"gamepad":{"axes":[0,0,0],"buttons":[]}})"), "gamepad.axes");
  EXPECT_EQ(input_error(R"({"stop":1})"), "input.stop");
  EXPECT_EQ(input_error(R"({"stop_reason":7})"), "input.stop_reason");
  EXPECT_EQ(input_error(R"({"halt":true})"), "input.halt");
  EXPECT_EQ(input_error("[]"), "input");
  EXPECT_EQ(runtime_error_field(R"({"behaviours":{"slant":false}})"), "runtime.behaviours.slant");
  EXPECT_EQ(runtime_error_field(R"({"max_drop_v":0})"), "runtime.max_drop_v");
  EXPECT_EQ(runtime_error_field(R"({"speed_scale":1.5})"), "runtime.speed_scale");
  EXPECT_EQ(runtime_error_field(R"({"load_distribution":"x"})"), "runtime.load_distribution");
  EXPECT_EQ(runtime_error_field(R"({"supply":"mains"})"), "runtime.supply");
  EXPECT_EQ(runtime_error_field(R"({"supply":true})"), "runtime.supply");
  EXPECT_EQ(runtime_error_field(R"({"behaviours":true})"), "runtime.behaviours");
  EXPECT_EQ(runtime_error_field(R"({"max_drop":1})"), "runtime.max_drop");
  // A FieldError is an std::invalid_argument, what the scenario reader catches.
  EXPECT_THROW(runtime_settings_from_json(json::parse(R"({"speed_scale":-1})"), {}),
               std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::link
