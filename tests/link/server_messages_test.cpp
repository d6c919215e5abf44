// The server's messages as docs/operator-protocol.md shows them.
#include "link/server_messages.hpp"

#include <gtest/gtest.h>

namespace marsokhod::link {
namespace {

TEST(ServerMessages, HelloSaysWhoHoldsControlWhichCalibrationTheDriverLoadedAndTheVelocityLimits) {
  const VelocityLimits limits{0.25, 0.5};
  EXPECT_EQ(hello_json(3, std::nullopt, {}, limits),
            nlohmann::json::parse(
                R"({"type":"hello","protocol":2,"client_id":3,"controller":null,"read_only":true,
                    "calibration":{"file":null,"procedures":[]},
                    "velocity_limits":{"v_mps":0.25,"yaw_radps":0.5}})"));
  EXPECT_EQ(hello_json(3, 1, {}, limits)["controller"], 1);
  const nlohmann::json calibrated =
      hello_json(3, 1, config::CalibrationSource{"rover7.toml", {"voltage", "motor-scale"}}, limits);
  EXPECT_EQ(calibrated["calibration"]["file"], "rover7.toml");
  EXPECT_EQ(calibrated["calibration"]["procedures"], nlohmann::json({"voltage", "motor-scale"}));
}

TEST(ServerMessages, TheVelocityLimitsAreTheOnesTheVelocityMessageIsCheckedAgainst) {
  // The default rover: r·v1ᵈ = 0.125 m · 2.25 rad/s and r·v2ᵈ/(t/2) = 0.125 m · 1.5 rad/s / 0.35 m.
  Params params;
  const VelocityLimits limits = velocity_limits(params);
  EXPECT_NEAR(limits.v_mps, 0.125 * 2.25, 1e-12);
  EXPECT_NEAR(limits.yaw_radps, 0.125 * 1.5 / 0.35, 1e-12);
  // A slower operator limit is a slower console: the limits follow the parameters.
  params.operator_input.max_drive_speed_radps = 1.0;
  EXPECT_NEAR(velocity_limits(params).v_mps, 0.125, 1e-12);
}

TEST(ServerMessages, ControlTellsThePreviousControllerItLostControl) {
  const ControlChange change{2, 1, "client 2 took control from client 1"};
  const nlohmann::json previous = control_json(change, 1);
  EXPECT_EQ(previous["type"], "control");
  EXPECT_EQ(previous["controller"], 2);
  EXPECT_EQ(previous["read_only"], true);
  EXPECT_EQ(previous["lost_control"], true);
  EXPECT_EQ(previous["reason"], "client 2 took control from client 1");
  EXPECT_EQ(control_json(change, 2)["read_only"], false);
  EXPECT_EQ(control_json(change, 2)["lost_control"], false);
  EXPECT_EQ(control_json(change, 3)["lost_control"], false);
  EXPECT_TRUE(control_json({std::nullopt, 1, "released"}, 3)["controller"].is_null());
}

TEST(ServerMessages, ErrorsPongAndStatus) {
  EXPECT_EQ(error_json({"axes[1]", "too big"}),
            nlohmann::json::parse(R"({"type":"error","field":"axes[1]","message":"too big"})"));
  EXPECT_EQ(pong_json(), nlohmann::json::parse(R"({"type":"pong"})"));
  EXPECT_EQ(stopped_json({3, "client 3 pressed STOP"}),
            nlohmann::json::parse(R"({"type":"stopped","by":3,"reason":"client 3 pressed STOP"})"));
  EXPECT_EQ(status_envelope({{"cycle", 4}})["status"]["cycle"], 4);
  EXPECT_EQ(status_envelope({{"cycle", 4}})["type"], "status");
}

TEST(ServerMessages, WireTextReplacesInvalidUtf8) {
  const std::string text = wire_text({{"lcd", std::string("ok\xff")}});
  EXPECT_EQ(text, "{\"lcd\":\"ok\xef\xbf\xbd\"}");
}

}  // namespace
}  // namespace marsokhod::link
