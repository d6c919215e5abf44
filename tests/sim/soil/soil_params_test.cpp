#include "sim/soil/soil_params.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "../../support/invalid_argument.hpp"

namespace marsokhod::sim::soil {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// The default sand is Wong's dry sand, in SI units (kN → N, kPa → Pa), with K = 10 mm.
TEST(SoilParams, DrySandIsWongsTable) {
  const SoilParams sand = dry_sand();
  EXPECT_EQ(sand.name, "sand");
  EXPECT_DOUBLE_EQ(sand.sinkage_exponent, 1.1);
  EXPECT_DOUBLE_EQ(sand.cohesive_modulus, 990.0);
  EXPECT_DOUBLE_EQ(sand.frictional_modulus, 1528430.0);
  EXPECT_DOUBLE_EQ(sand.cohesion_pa, 1040.0);
  EXPECT_NEAR(sand.friction_angle_rad, 28.0 * kDeg, 1e-8);
  EXPECT_DOUBLE_EQ(sand.shear_modulus_m, 0.010);
  EXPECT_NEAR(sand.soil_metal_friction_angle_rad, 15.0 * kDeg, 1e-8);
  EXPECT_NO_THROW(validate(sand));
}

TEST(SoilParams, LunarSoilIsDingsTable) {
  const SoilParams lunar = lunar_soil();
  EXPECT_DOUBLE_EQ(lunar.sinkage_exponent, 1.0);
  EXPECT_DOUBLE_EQ(lunar.cohesive_modulus, 1400.0);
  EXPECT_DOUBLE_EQ(lunar.frictional_modulus, 820000.0);
  EXPECT_DOUBLE_EQ(lunar.cohesion_pa, 170.0);
  EXPECT_NEAR(lunar.friction_angle_rad, 35.0 * kDeg, 1e-12);
  EXPECT_DOUBLE_EQ(lunar.shear_modulus_m, 0.018);
  EXPECT_NEAR(lunar.bulk_density_kgpm3 * lunar.gravity_mps2, 2470.0, 1e-9);
  EXPECT_NO_THROW(validate(lunar));
}

// Chapter 3.1: r = 0.115 m on granules, 0.125 m with the blades; i = 0.240 rad.
TEST(SoilParams, MarsokhodWheelIsChapter31s) {
  const WheelGeometry wheel;
  EXPECT_DOUBLE_EQ(wheel.rim_radius_m, 0.115);
  EXPECT_DOUBLE_EQ(wheel.shear_radius_m(), 0.125);
  EXPECT_DOUBLE_EQ(wheel.blade_inclination_rad, 0.240);
  EXPECT_NO_THROW(validate(wheel));
}

TEST(SoilParams, RejectsBadSoilWithTheParameterAndItsRange) {
  const auto expect_rejected = [](auto change, std::initializer_list<std::string> fragments) {
    SoilParams soil = dry_sand();
    change(soil);
    test_support::expect_invalid_argument([&] { validate(soil); }, fragments);
  };
  expect_rejected([](SoilParams& s) { s.sinkage_exponent = test_support::kNaN; },
                  {"soil 'sand'", "sinkage_exponent", "nan"});
  expect_rejected([](SoilParams& s) { s.frictional_modulus = -1.0; }, {"k_phi", "-1"});
  expect_rejected(
      [](SoilParams& s) {
        s.frictional_modulus = 0.0;
        s.cohesive_modulus = 0.0;
      },
      {"carry no load"});
  expect_rejected([](SoilParams& s) { s.shear_modulus_m = 0.0; }, {"shear_modulus_m (K)"});
  expect_rejected([](SoilParams& s) { s.friction_angle_rad = 2.0; }, {"friction_angle_rad"});
  expect_rejected([](SoilParams& s) { s.repose_angle_rad = 1.6; }, {"repose_angle_rad"});
  expect_rejected([](SoilParams& s) { s.displaced_fraction = 1.5; }, {"displaced_fraction"});
  expect_rejected([](SoilParams& s) { s.cohesion_pa = test_support::kInf; }, {"cohesion_pa"});
}

TEST(SoilParams, RejectsBadWheel) {
  WheelGeometry wheel;
  wheel.rim_radius_m = 0.0;
  test_support::expect_invalid_argument([&] { validate(wheel); }, {"rim_radius_m", "got 0"});
  wheel = WheelGeometry{};
  wheel.blade_height_m = 0.2;
  test_support::expect_invalid_argument([&] { validate(wheel); }, {"blade_height_m"});
  wheel = WheelGeometry{};
  wheel.lanes = 0;
  test_support::expect_invalid_argument([&] { validate(wheel); }, {"lanes", "got 0"});
  wheel = WheelGeometry{};
  wheel.arc_samples = 2;
  test_support::expect_invalid_argument([&] { validate(wheel); }, {"arc_samples"});
  wheel = WheelGeometry{};
  wheel.handedness = static_cast<BladeHandedness>(0);
  test_support::expect_invalid_argument([&] { validate(wheel); }, {"handedness"});
}

}  // namespace
}  // namespace marsokhod::sim::soil
