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
    s.motors[i] = {k,     k + 0.5, k / 1024.0, k + 0.25, k + 0.125, 0.125,
                   4.125, k - 0.5, k / 16.0,   k / 8.0,  static_cast<int>(i)};
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
  s.stalled_s = 1.25;
  s.joint_stalled_s = {2.5, 0.0};
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
  EXPECT_EQ(j["stalled_s"], 1.25);
  EXPECT_EQ(j["joint_stalled_s"], nlohmann::json({2.5, 0.0}));
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
    EXPECT_EQ(m["position_uncertainty_rad"], k / 1024.0);
    EXPECT_EQ(m["velocity_radps"], k + 0.25);
    EXPECT_EQ(m["no_load_velocity_radps"], k + 0.125);
    EXPECT_EQ(m["load_radps"], 0.125);
    EXPECT_EQ(m["torque_nm"], 4.125);
    EXPECT_EQ(m["commanded_radps"], k - 0.5);
    EXPECT_EQ(m["slope_hold_radps"], k / 16.0);
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

// The 3-D view's ruts (issue #14): every second cell of the grid around the rover, the patch's
// corner on those cells, the surface in mm.
TEST(StatusJson, SoilPatchSamplesEverySecondCellAroundThePoint) {
  const sim::soil::GridSpec spec{-3.0, -3.0, 0.02, 300, 300};
  sim::soil::SoilGrid grid(spec, sim::soil::dry_sand(), [](double, double) { return 0.0; });
  grid.set_cell_surface_m(150, 110, -0.025);  // a rut at (0.01, −0.79)
  grid.set_cell_surface_m(151, 110, -0.040);  // an odd cell: not sampled
  const nlohmann::json patch = soil_patch_json(grid, 0.2, 0.0);
  // x within 0.2 ± 1.6 m: sampled cells 80, 82, … 238 (centres −1.39 … 1.77), 80 columns; y within
  // ±1.0 m: cells 100 … 198 (−0.99 … 0.97), 50 rows.
  ASSERT_EQ(patch["columns"], 80);
  ASSERT_EQ(patch["rows"], 50);
  EXPECT_DOUBLE_EQ(patch["cell_m"].get<double>(), 0.04);
  EXPECT_NEAR(patch["origin_m"][0].get<double>(), -1.39, 1e-12);
  EXPECT_NEAR(patch["origin_m"][1].get<double>(), -0.99, 1e-12);
  const auto& heights = patch["height_mm"];
  ASSERT_EQ(heights.size(), 80u * 50u);
  // Cell (150, 110) is column 150/2 − 40 = 35, row 110/2 − 50 = 5: at (−1.39 + 35·0.04,
  // −0.99 + 5·0.04) = (0.01, −0.79), its centre.
  EXPECT_EQ(heights[5 * 80 + 35], -25);
  long others = 0;
  for (const auto& h : heights) others += h.get<long>() != 0 ? 1 : 0;
  EXPECT_EQ(others, 1);
  // 10 cm further along x the corner moves to the next sampled cell within reach, (0.3 − 1.6 +
  // 3 − 0.01)/0.04 = 42.25 → 43: three columns on (no shimmer), the rut three to the left.
  const nlohmann::json moved = soil_patch_json(grid, 0.3, 0.0);
  EXPECT_NEAR(moved["origin_m"][0].get<double>(), -1.39 + 3 * 0.04, 1e-12);
  EXPECT_EQ(moved["height_mm"][5 * 80 + 32], -25);
  // Where the span's start falls exactly on a sampled cell's centre, still 80 × 50 samples
  // (span/step of them, not one more): x = −1.39 + 1.6 = 0.21, y = −0.99 + 1.0 = 0.01.
  const nlohmann::json exact = soil_patch_json(grid, 0.21, 0.01);
  EXPECT_EQ(exact["columns"], 80);
  EXPECT_EQ(exact["rows"], 50);
  EXPECT_NEAR(exact["origin_m"][0].get<double>(), -1.39, 1e-12);
  // No position, no patch.
  EXPECT_EQ(soil_patch_json(grid, std::nan(""), 0.0)["columns"], 0);
}

TEST(StatusJson, SoilPatchIsClippedToTheGrid) {
  const sim::soil::GridSpec spec{-1.0, -1.0, 0.02, 100, 100};
  const sim::soil::SoilGrid grid(spec, sim::soil::dry_sand(),
                                 [](double x, double) { return 0.1 * x; });  // a slope
  const nlohmann::json patch = soil_patch_json(grid, 0.9, 0.0);
  // x: from 0.9 − 1.6 = −0.7 to the grid's last sampled cell, 98 (0.97): cells 16, 18, … 98
  // (−0.67 … 0.97), 42 columns.
  ASSERT_EQ(patch["columns"], 42);
  ASSERT_EQ(patch["rows"], 50);
  EXPECT_NEAR(patch["origin_m"][0].get<double>(), -0.67, 1e-12);
  // The undisturbed slope is in the heights: 0.1·x, in mm.
  EXPECT_EQ(patch["height_mm"][0], -67);
  EXPECT_EQ(patch["height_mm"][41], 97);
  // Far off the grid: an empty patch, not an error.
  const nlohmann::json off = soil_patch_json(grid, 10.0, 10.0);
  EXPECT_EQ(off["columns"], 0);
  EXPECT_TRUE(off["height_mm"].empty());
}

TEST(StatusJson, TruthCarriesTheSoilOnlyOnSoftSoilAndWhenAsked) {
  const Params params;
  sim::SimOptions soft;
  soft.terrain.ground = sim::sand();
  const sim::SimulatedRover on_sand(params, soft);
  EXPECT_FALSE(truth_json(on_sand).contains("soil"));
  const nlohmann::json truth = truth_json(on_sand, std::nullopt, true);
  ASSERT_TRUE(truth.contains("soil"));
  EXPECT_EQ(truth["soil"]["columns"], 80);
  EXPECT_EQ(truth["soil"]["rows"], 50);
  const sim::SimulatedRover on_hard(params, sim::SimOptions{});
  EXPECT_FALSE(truth_json(on_hard, std::nullopt, true).contains("soil"));
}

}  // namespace
}  // namespace marsokhod::link
