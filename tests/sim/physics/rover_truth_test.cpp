// What the simulator knows and a sensor would read, checked against physics worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "physics_test_support.hpp"
#include "sim/physics/rover_mjcf.hpp"
#include "sim/physics/rover_physics.hpp"

namespace marsokhod::sim {
namespace {

using testing::all_wheels;
using testing::drive_at;
using testing::expect_healthy;
using testing::run;

constexpr double kGravity = 9.81;

TEST(RoverTruth, AtRestOnFlatGroundTheAccelerometerReadsGravity) {
  RoverPhysics physics(Params{}, TerrainSpec{});
  run(physics, 500);
  const ImuTruth imu = physics.imu();
  EXPECT_NEAR(imu.accel_mps2[0], 0.0, 1e-3);
  EXPECT_NEAR(imu.accel_mps2[1], 0.0, 1e-3);
  EXPECT_NEAR(imu.accel_mps2[2], -kGravity, 1e-3);  // (3.5): gravity minus acceleration
  EXPECT_NEAR(imu.yaw_rate_radps, 0.0, 1e-6);
  EXPECT_NEAR(imu.front_tilt_rad, 0.0, 1e-6);
  const GroundTruth truth = physics.truth();
  EXPECT_NEAR(truth.position_m[2], 0.125, 2e-3);  // the center axle one wheel radius up
  for (bool touching : truth.wheel_contact) EXPECT_TRUE(touching);
  EXPECT_NEAR(truth.roll_pitch_yaw_rad[1], 0.0, 1e-4);
  expect_healthy(physics);
}

// Nose up on a 15° slope, the wheels held: gravity seen from the center unit, with x1 forward and
// x3 up, is (−g·sin 15°, 0, −g·cos 15°); the pitch by the right-hand rule about x2 is −15°.
TEST(RoverTruth, OnAFifteenDegreeSlopeTheAccelerometerSeesTheSlope) {
  RoverPhysics physics(Params{}, testing::slope_deg(15.0));
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) physics.set_wheel_blocked(wheel, true);
  run(physics, 1000);
  const double slope = 15.0 * std::numbers::pi / 180.0;
  const ImuTruth imu = physics.imu();
  EXPECT_NEAR(imu.accel_mps2[0], -kGravity * std::sin(slope), 0.01);
  EXPECT_NEAR(imu.accel_mps2[1], 0.0, 0.01);
  EXPECT_NEAR(imu.accel_mps2[2], -kGravity * std::cos(slope), 0.01);
  const GroundTruth truth = physics.truth();
  EXPECT_NEAR(truth.roll_pitch_yaw_rad[1], -slope, 2e-3);
  EXPECT_NEAR(std::hypot(truth.velocity_mps[0], truth.velocity_mps[2]), 0.0, 1e-3);  // at rest
  expect_healthy(physics);
}

// Chapter 5: v1 = 2 rad/s on all six wheels drives the rover at ≈ ω·r on hard ground.
TEST(RoverTruth, DrivingStraightAdvancesAtWheelSpeedTimesRadius) {
  RoverPhysics physics(Params{}, TerrainSpec{});
  run(physics, 300);
  physics.set_drive(drive_at(all_wheels(2.0)));
  run(physics, 700);  // the wheels spin up within ~50 ms
  const double start_m = physics.truth().position_m[0];
  const double start_angle = physics.shaft_angle_rad()[kCenterLeft];
  run(physics, 2000);
  const GroundTruth truth = physics.truth();
  const double advance_m = truth.position_m[0] - start_m;
  const double rolled_m = (physics.shaft_angle_rad()[kCenterLeft] - start_angle) * 0.125;
  EXPECT_NEAR(advance_m, 2.0 * 0.125 * 2.0, 0.01);  // 2 s at 0.25 m/s
  EXPECT_NEAR(advance_m / rolled_m, 1.0, 0.01);
  EXPECT_NEAR(truth.position_m[1], 0.0, 0.01);  // straight
  EXPECT_NEAR(truth.velocity_mps[0], 0.25, 0.003);
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    EXPECT_NEAR(truth.wheel_slip_mps[wheel], 0.0, 2e-3) << wheel;
    EXPECT_TRUE(truth.wheel_contact[wheel]) << wheel;
  }
  expect_healthy(physics);
}

// m2 of chapter 5.1: left side backward, right forward, the exterior wheels F(c) = 5.3c + 0.04
// times faster: the rover spins about the center axle, to the left (positive yaw rate about x3).
TEST(RoverTruth, SpinningWithM2ShowsOnTheGyro) {
  const Params params;
  RoverPhysics physics(params, TerrainSpec{});
  run(physics, 300);
  const double c = std::sqrt(0.413 * 0.413 - 0.145 * 0.145);
  const double f = params.spin.slope_per_m * c + params.spin.offset;
  const double v2 = 1.0;
  physics.set_drive(drive_at({-f * v2, f * v2, -v2, v2, -f * v2, f * v2, 0.0, 0.0}));
  run(physics, 1000);
  const double yaw_start = physics.truth().roll_pitch_yaw_rad[2];
  run(physics, 2000);
  const GroundTruth truth = physics.truth();
  const double mean_rate = (truth.roll_pitch_yaw_rad[2] - yaw_start) / 2.0;
  // Below the no-slip rate of the center wheels, v2·r/(track/2) = 0.357 rad/s: skidding costs.
  EXPECT_GT(mean_rate, 0.15);
  EXPECT_LT(mean_rate, 0.357);
  EXPECT_GT(physics.imu().yaw_rate_radps, 0.1);
  EXPECT_NEAR(std::hypot(truth.position_m[0], truth.position_m[1]), 0.0, 0.03);  // in place
  // The exterior wheels turn faster than the ground lets them: they slip; left backward.
  EXPECT_LT(truth.wheel_slip_mps[kFrontLeft], -0.05);
  EXPECT_GT(truth.wheel_slip_mps[kFrontRight], 0.05);
  expect_healthy(physics);
}

// A ground with rolling friction (terrain.hpp: MuJoCo's condim 6, C_rr·r) resists rolling: the same
// wheel speed takes torque that hard ground does not ask for.
TEST(RoverTruth, RollingFrictionTakesTorqueThatHardGroundDoesNot) {
  const auto cruise_torque = [](const Material& material) {
    TerrainSpec terrain;
    terrain.ground = material;
    RoverPhysics physics(Params{}, terrain);
    physics.set_drive(drive_at(all_wheels(2.0)));
    run(physics, 2000);
    double sum_nm = 0.0;
    for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel)
      sum_nm += physics.shaft_torque_nm()[wheel];
    expect_healthy(physics);
    return sum_nm;
  };
  const double hard_nm = cruise_torque(hard_ground());
  const double rolling_nm = cruise_torque(Material{0.5, 0.0, 0.02});
  EXPECT_NEAR(hard_nm, 0.0, 0.5);
  // C_rr·r·m·g = 0.02 m · 82 kg · 9.81 m/s² ≈ 16 N·m over six wheels.
  EXPECT_NEAR(rolling_nm, 0.02 * 82.0 * kGravity, 4.0);
}

TEST(RoverTruth, TotalMassIsRealistic) {
  const RoverPhysics physics(Params{}, TerrainSpec{});
  EXPECT_GE(physics.total_mass_kg(), 70.0);
  EXPECT_LE(physics.total_mass_kg(), 100.0);
}

// A tree trunk 16 cm thick lying across the path 1 m ahead (chapter 2, Figure 1.1).
TerrainSpec tree_trunk_course() {
  TerrainSpec course;
  course.kind = TerrainKind::kObstacles;
  Obstacle trunk;
  trunk.shape = ObstacleShape::kCylinder;
  trunk.center_m = {1.0, 0.0, 0.08};
  trunk.cylinder_radius_m = 0.08;
  trunk.cylinder_length_m = 2.0;
  trunk.roll_pitch_yaw_rad = {std::numbers::pi / 2, 0.0, 0.0};
  course.obstacles = {trunk};
  return course;
}

// The model builds and the rover stands on every kind of terrain.
TEST(RoverTruth, StandsOnEveryTerrainKind) {
  TerrainSpec plateau;
  plateau.kind = TerrainKind::kHeightfield;
  plateau.heightfield.image = GrayImage{3, 3, std::vector<double>(9, 0.5)};
  plateau.heightfield.max_height_m = 0.4;
  const TerrainSpec course = tree_trunk_course();
  const std::array<std::pair<TerrainSpec, double>, 4> cases{{{TerrainSpec{}, 0.125},
                                                             {testing::slope_deg(10.0), 0.125},
                                                             {course, 0.125},
                                                             {plateau, 0.2 + 0.125}}};
  for (const auto& [terrain, height_m] : cases) {
    SCOPED_TRACE(to_string(terrain.kind));
    RoverPhysics physics(Params{}, terrain);
    for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel)
      physics.set_wheel_blocked(wheel, true);
    run(physics, 500);
    const GroundTruth truth = physics.truth();
    // Height above the ground along its normal, (−sin β, 0, cos β) on a slope of β.
    const double slope = terrain.kind == TerrainKind::kSlope ? terrain.slope_rad : 0.0;
    const double clearance_m =
        truth.position_m[2] * std::cos(slope) - truth.position_m[0] * std::sin(slope);
    EXPECT_NEAR(clearance_m, height_m, 3e-3);
    for (bool touching : truth.wheel_contact) EXPECT_TRUE(touching);
    expect_healthy(physics);
  }
}

// Chapter 2's "stones got stuck between the blades": a trunk 16 cm thick across the path is
// climbed at 0.25 m/s.
TEST(RoverTruth, ClimbsOverATreeTrunk) {
  const TerrainSpec course = tree_trunk_course();
  RoverPhysics physics(Params{}, course);
  physics.set_drive(drive_at(all_wheels(2.0)));
  double highest_m = 0.0;
  for (int step = 0; step < 12000; ++step) {
    physics.step();
    highest_m = std::max(highest_m, physics.truth().wheel_position_m[kCenterLeft][2]);
  }
  EXPECT_GT(physics.truth().position_m[0], 1.8);  // the whole rover beyond the trunk
  EXPECT_GT(highest_m, 0.125 + 0.1);              // the center wheels went over it
  expect_healthy(physics);
}

}  // namespace
}  // namespace marsokhod::sim
