// status_json: every DriverStatus field under its key, motors by name, units in the keys, the
// caller's ground truth attached as given; truth_json: the simulator's truth the 3-D view reads.
#include "link/status_json.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace marsokhod::link {
namespace {

driver::DriverStatus sample_status() {
  driver::DriverStatus s;
  s.mission_time_s = 12.5;
  s.cycle_time_s = 0.0156;
  s.cycle = 801;
  s.mode = driver::DriverMode::kDriving;
  s.startup_phase = driver::StartupPhase::kDone;
  s.supply_v = 23.5;
  s.reference_supply_v = 24.0;
  s.yaw_rate_radps = -0.25;
  s.accel_mps2 = {0.5, -0.25, -9.75};
  s.front_tilt_rad = -1.5;
  s.rear_tilt_rad = 1.25;
  s.slope_rad = 0.125;
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    const double k = static_cast<double>(i);
    s.motors[i] = {k,     k + 0.5, k + 0.25, k + 0.125,          0.125,
                   4.125, k - 0.5, k / 8.0,  static_cast<int>(i)};
  }
  s.sensor_silent_cycles = 2;
  s.max_duty = 0.75;
  s.driving_scale = 0.5;
  s.walking_scale = 0.25;
  s.targets = {1.0, 0.5, 0.75, 0.25, 0.125, -0.125};
  s.commands = {0.5, 0.25, -0.375, 0.0, 0.0, -0.0625};
  s.gait = mobility::Gait::kFrontWheelWalking;
  s.gait_state = 1;
  s.gait_speed = -0.5;
  s.front_axle_factor = 1.0;
  s.rear_axle_factor = 0.5;
  s.joint_bounds = {-2.55, -1.2121, 1.2121, 2.0};
  s.joints_known = false;
  s.joint_origin = "unknown: µ6 reset";
  s.operator_timeout = false;
  s.operator_rejection = "v1 = 9 is out of range";
  s.faults = {"µ3 silent"};
  s.warnings = {"supply 19.8 V near the brown-out voltage"};
  s.bus = {100, 1, 2, 3, 4, "bad dlc"};
  s.lcd = "24.0V ok";
  s.settings.max_drop_v = 2.5;
  s.settings.speed_scale = 0.5;
  s.settings.switches.load_distribution = LoadDistributionMode::kSlip;
  s.settings.switches.power_management = true;
  s.settings.switches.slant_response = false;
  s.settings.switches.contract_on_turn = true;
  s.settings.switches.axle_placement = false;
  return s;
}

TEST(StatusJson, CarriesEveryFieldUnderItsKey) {
  const nlohmann::json j = status_json(sample_status());
  EXPECT_EQ(j["mission_time_s"], 12.5);
  EXPECT_EQ(j["cycle_time_s"], 0.0156);
  EXPECT_EQ(j["cycle"], 801);
  EXPECT_EQ(j["mode"], "driving");
  EXPECT_EQ(j["startup_phase"], driver::phase_name(driver::StartupPhase::kDone));
  EXPECT_EQ(j["supply_v"], 23.5);
  EXPECT_EQ(j["reference_supply_v"], 24.0);
  EXPECT_EQ(j["yaw_rate_radps"], -0.25);
  EXPECT_EQ(j["accel_mps2"], nlohmann::json({0.5, -0.25, -9.75}));
  EXPECT_EQ(j["front_tilt_rad"], -1.5);
  EXPECT_EQ(j["rear_tilt_rad"], 1.25);
  EXPECT_EQ(j["slope_rad"], 0.125);
  EXPECT_EQ(j["sensor_silent_cycles"], 2);
  EXPECT_EQ(j["max_duty"], 0.75);
  EXPECT_EQ(j["driving_scale"], 0.5);
  EXPECT_EQ(j["walking_scale"], 0.25);
  EXPECT_EQ(j["targets"]["v7_radps"], -0.125);
  EXPECT_EQ(j["targets"]["v3_radps"], 0.75);
  EXPECT_EQ(j["commands"]["v3_radps"], -0.375);
  EXPECT_EQ(j["commands"]["v1_radps"], 0.5);
  EXPECT_EQ(j["gait"]["id"], "front-wheel-walking");
  EXPECT_EQ(j["gait"]["name"], "front-wheel walking");
  EXPECT_EQ(j["gait"]["state"], 1);
  EXPECT_EQ(j["gait"]["speed"], -0.5);
  EXPECT_EQ(j["front_axle_factor"], 1.0);
  EXPECT_EQ(j["rear_axle_factor"], 0.5);
  EXPECT_EQ(j["joint_bounds"]["rear_max_rad"], 2.0);
  EXPECT_EQ(j["joints_known"], false);
  EXPECT_EQ(j["joint_origin"], "unknown: µ6 reset");
  EXPECT_EQ(j["operator_timeout"], false);
  EXPECT_EQ(j["operator_rejection"], "v1 = 9 is out of range");
  EXPECT_EQ(j["faults"], nlohmann::json({"µ3 silent"}));
  EXPECT_EQ(j["warnings"].size(), 1U);
  EXPECT_EQ(j["bus"]["frames"], 100);
  EXPECT_EQ(j["bus"]["missed"], 4);
  EXPECT_EQ(j["bus"]["last_error"], "bad dlc");
  EXPECT_EQ(j["lcd"], "24.0V ok");
  EXPECT_FALSE(j.contains("truth"));
  // The settings in force, in configure's own keys: the console's form shows them.
  EXPECT_EQ(j["settings"], nlohmann::json::parse(R"({"max_drop_v":2.5,"load_distribution":"s",
      "behaviours":{"power_management":true,"slant_response":false,"contract_on_turn":true,
      "axle_placement":false},"speed_scale":0.5,"supply":"battery"})"));
}

TEST(StatusJson, KeysEveryMotorByItsName) {
  const nlohmann::json motors = status_json(sample_status())["motors"];
  ASSERT_EQ(motors.size(), kMotorCount);
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    const nlohmann::json& m = motors.at(kMotorNames[i]);
    const double k = static_cast<double>(i);
    EXPECT_EQ(m["shaft_position_rad"], k);
    EXPECT_EQ(m["position_rad"], k + 0.5);
    EXPECT_EQ(m["velocity_radps"], k + 0.25);
    EXPECT_EQ(m["no_load_velocity_radps"], k + 0.125);
    EXPECT_EQ(m["load_radps"], 0.125);
    EXPECT_EQ(m["torque_nm"], 4.125);
    EXPECT_EQ(m["commanded_radps"], k - 0.5);
    EXPECT_EQ(m["duty"], k / 8.0);
    EXPECT_EQ(m["silent_cycles"], static_cast<int>(i));
  }
  EXPECT_EQ(motors["AR"]["silent_cycles"], 7);
}

TEST(StatusJson, AttachesTheCallersTruth) {
  const nlohmann::json truth = {{"chassis_position_m", {1.0, 2.0, 0.3}}};
  EXPECT_EQ(status_json(sample_status(), truth)["truth"], truth);
  EXPECT_THROW(status_json(sample_status(), nlohmann::json::array()), std::invalid_argument);
}

TEST(StatusJson, WritesNonFiniteNumbersAsNull) {
  driver::DriverStatus s = sample_status();
  s.supply_v = std::numeric_limits<double>::quiet_NaN();
  s.motors[kFrontJoint].load_radps = std::numeric_limits<double>::infinity();
  const nlohmann::json back = nlohmann::json::parse(status_json(s).dump());
  EXPECT_TRUE(back["supply_v"].is_null());
  EXPECT_TRUE(back["motors"]["AF"]["load_radps"].is_null());
}

TEST(StatusJson, TruthHasTheKeysTheThreeDViewReads) {
  const Params params;
  const sim::SimulatedRover rover(params, sim::SimOptions{});
  const nlohmann::json truth = truth_json(rover);
  EXPECT_EQ(truth["position_m"].size(), 3u);
  EXPECT_EQ(truth["roll_pitch_yaw_rad"].size(), 3u);
  EXPECT_EQ(truth["velocity_mps"].size(), 3u);
  EXPECT_EQ(truth["joint_angle_rad"].size(), kMotorCount);
  ASSERT_EQ(truth["wheel_angle_rad"].size(), kWheelCount);
  EXPECT_EQ(truth["wheel_angle_rad"][5], truth["joint_angle_rad"][5]);
  ASSERT_EQ(truth["wheel_position_m"].size(), kWheelCount);
  EXPECT_EQ(truth["wheel_position_m"][0].size(), 3u);
  EXPECT_EQ(truth["wheel_slip_mps"].size(), kWheelCount);
  EXPECT_EQ(truth["supply_v"], rover.electrics().supply_v);
  EXPECT_EQ(truth["computer_on"], true);
  EXPECT_EQ(status_json(sample_status(), truth)["truth"], truth);
  EXPECT_FALSE(truth.contains("odometry"));
}

TEST(StatusJson, TruthCarriesThePoseInTheOdometryFrameWhenGiven) {
  const Params params;
  const sim::SimulatedRover rover(params, sim::SimOptions{});
  const nlohmann::json truth = truth_json(rover, estimation::PlanarPose{1.5, -0.25, 3.5});
  ASSERT_TRUE(truth.contains("odometry"));
  EXPECT_EQ(truth["odometry"],
            (nlohmann::json{{"x_m", 1.5}, {"y_m", -0.25}, {"heading_rad", 3.5}}));
  EXPECT_EQ(truth["position_m"].size(), 3u);
}

}  // namespace
}  // namespace marsokhod::link
