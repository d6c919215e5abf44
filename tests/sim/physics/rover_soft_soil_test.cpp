// The rover on soft soil (rover_soft_soil.cpp): the wheels carried by the sim/soil model through
// xfrc_applied instead of MuJoCo contacts. Every scenario counts exact steps of 1 ms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "physics_test_support.hpp"
#include "sim/physics/rover_physics.hpp"

namespace marsokhod::sim {
namespace {

using testing::all_wheels;
using testing::drive_at;
using testing::expect_healthy;
using testing::run;

TerrainSpec soft_flat() {
  TerrainSpec terrain;
  terrain.ground = soft_sand();
  return terrain;
}

// Standing unpowered on soft sand the rover sinks in — the centre wheels, under the centre unit's
// 30 kg, deepest: 1–3 cm below the 0.115 m rim (the blades' 1 cm more) — and stays put: the soil
// holds it without a push along the ground.
TEST(RoverSoftSoil, StandsOnSoftSandAndSinksIn) {
  RoverPhysics soft(Params{}, soft_flat());
  run(soft, 2000);
  const GroundTruth start = soft.truth();
  run(soft, 1000);
  const GroundTruth end = soft.truth();
  expect_healthy(soft);
  for (std::size_t wheel : {kCenterLeft, kCenterRight}) {
    const double rim_depth = 0.115 - end.wheel_position_m[wheel][2];
    EXPECT_GT(rim_depth, 0.01) << kMotorNames[wheel];
    EXPECT_LT(rim_depth, 0.03) << kMotorNames[wheel];
  }
  EXPECT_LT(
      std::hypot(end.position_m[0] - start.position_m[0], end.position_m[1] - start.position_m[1]),
      0.002);
  EXPECT_LT(std::abs(end.position_m[2] - start.position_m[2]), 0.002);
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) EXPECT_TRUE(end.wheel_contact[wheel]);
}

// Driving on soft sand: the rover advances, less than on hard ground, its wheels slipping on
// average (the drawbar pull of sand's compaction resistance needs slip, wheel_stress_test).
TEST(RoverSoftSoil, DrivesForwardWithSlip) {
  const auto driven = [](const TerrainSpec& terrain, double& mean_slip_mps, double& lateral_m) {
    RoverPhysics physics(Params{}, terrain);
    run(physics, 500);
    const double start = physics.truth().position_m[0];
    physics.set_drive(drive_at(all_wheels(2.0)));
    run(physics, 2000);
    mean_slip_mps = 0.0;
    for (int i = 0; i < 1000; ++i) {
      physics.step();
      for (double slip : physics.truth().wheel_slip_mps)
        mean_slip_mps += slip / (1000.0 * kWheelCount);
    }
    expect_healthy(physics);
    lateral_m = physics.truth().position_m[1];
    return physics.truth().position_m[0] - start;
  };
  double hard_slip = 0.0, soft_slip = 0.0, hard_lateral = 0.0, soft_lateral = 0.0;
  const double on_hard = driven(TerrainSpec{}, hard_slip, hard_lateral);
  const double on_soft = driven(soft_flat(), soft_slip, soft_lateral);
  EXPECT_GT(on_soft, 0.4);
  EXPECT_LT(on_soft, on_hard);
  EXPECT_GT(soft_slip, hard_slip);
  EXPECT_GT(soft_slip, 0.0);
  EXPECT_LT(std::abs(soft_lateral), 0.01);  // the blades' sideways pushes balance
}

// Up a soft-sand slope, driving all wheels at 2 rad/s: a wheel's drawbar pull reaches at most
// 0.24 of its load (wheel_stress_test), a 13.5° climb; the rover still gains ground on 10° and
// slides back on 25°, below sand's 28° angle of repose.
TEST(RoverSoftSoil, ClimbsTenDegreesButNotTwentyFive) {
  const auto advanced_m = [](double slope_deg) {
    TerrainSpec terrain = testing::slope_deg(slope_deg);
    terrain.ground = soft_sand();
    RoverPhysics physics(Params{}, terrain);
    run(physics, 500);
    const double start = physics.truth().position_m[0];
    physics.set_drive(drive_at(all_wheels(2.0)));
    run(physics, 5000);
    expect_healthy(physics);
    return physics.truth().position_m[0] - start;
  };
  EXPECT_GT(advanced_m(10.0), 0.3);
  EXPECT_LT(advanced_m(25.0), 0.0);
}

// The excavation of m4 (chapter 5.2, Field Experiment 6.3: "from a standing position, Marsokhod
// excavates a layer of up to 9 cm of sand" with the front-right wheel turning slowly): the front-
// right wheel alone at 1 rad/s, the others still. Slipping fully, its blades carry soil out of the
// rut and it sinks ≈ 3 mm/s; after ≈ 20 s it sinks no further, its blade tips 9.2 cm below the
// sand's surface (0.125 m − its centre's height), though it keeps spinning and slipping in its
// hole. The rest of the rover neither moves nor sinks.
TEST(RoverSoftSoil, TrenchWithTheFrontRightWheelDigsAboutNineCentimetres) {
  RoverPhysics physics(Params{}, soft_flat());
  run(physics, 2000);
  const GroundTruth standing = physics.truth();
  MotorVector trench{};
  trench[kFrontRight] = 1.0;
  physics.set_drive(drive_at(trench));
  const auto blade_depth_m = [&] {
    return 0.125 - physics.truth().wheel_position_m[kFrontRight][2];
  };
  const double at_rest = blade_depth_m();
  run(physics, 10000);
  const double after_10_s = blade_depth_m();
  run(physics, 15000);
  const double after_25_s = blade_depth_m();
  run(physics, 5000);
  const double after_30_s = blade_depth_m();
  const GroundTruth end = physics.truth();
  expect_healthy(physics);
  EXPECT_GT(after_10_s - at_rest, 0.02);  // digging
  EXPECT_NEAR(after_30_s, after_25_s, 0.002);  // and stopped
  EXPECT_GT(after_30_s, 0.07);
  EXPECT_LT(after_30_s, 0.11);
  for (std::size_t wheel : {kFrontLeft, kCenterLeft, kCenterRight, kBackLeft, kBackRight}) {
    EXPECT_NEAR(end.wheel_position_m[wheel][2], standing.wheel_position_m[wheel][2], 0.01)
        << kMotorNames[wheel];
  }
  EXPECT_LT(std::hypot(end.position_m[0] - standing.position_m[0],
                       end.position_m[1] - standing.position_m[1]),
            0.01);
}

TEST(RoverSoftSoil, TwoRunsAreBitIdentical) {
  const auto run_once = [] {
    RoverPhysics physics(Params{}, soft_flat());
    physics.set_drive(drive_at(all_wheels(1.5)));
    run(physics, 1500);
    return physics.truth().position_m;
  };
  const auto first = run_once(), second = run_once();
  EXPECT_EQ(std::memcmp(first.data(), second.data(), sizeof(first)), 0);
}

TEST(RoverSoftSoil, SoftSoilNeedsFlatOrSlopedGround) {
  TerrainSpec terrain;
  terrain.kind = TerrainKind::kHeightfield;
  terrain.ground = soft_sand();
  terrain.heightfield.image.width = 2;
  terrain.heightfield.image.height = 2;
  terrain.heightfield.image.values = {0.0, 0.0, 0.0, 0.0};
  EXPECT_THROW(validate(terrain), std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::sim
