#include "sim/physics/chassis_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace marsokhod::sim {
namespace {

const GeometryParams kThesis{};  // a = 0.145 m, b = 0.413 m

TEST(ChassisGeometry, VerticalJointsMatchRemark31AndTheTable) {
  EXPECT_NEAR(vertical_bend_rad(kThesis), 1.2121, 1e-4);  // Remark 3.1
  const double vertical = vertical_bend_rad(kThesis);
  // The lever hangs straight down: a right angle at the exterior axle.
  EXPECT_NEAR(axle_distance_m(kThesis, vertical), std::sqrt(0.413 * 0.413 - 0.145 * 0.145), 1e-12);
  // The chapter 3.1 table's largest elevation, 0.359 rad, is the vertical joint's.
  EXPECT_NEAR(strut_elevation_rad(kThesis, vertical), 0.359, 5e-4);
}

TEST(ChassisGeometry, LawOfCosinesAtTheBounds) {
  // γ = 2.55 (extended, (5.3)): c² = a² + b² − 2ab·cos 2.55.
  const double c = axle_distance_m(kThesis, 2.55);
  EXPECT_NEAR(c * c, 0.145 * 0.145 + 0.413 * 0.413 - 2 * 0.145 * 0.413 * std::cos(2.55), 1e-12);
  EXPECT_NEAR(c, 0.5395, 1e-4);
  // Extending lowers the strut toward the axles' line.
  EXPECT_LT(strut_elevation_rad(kThesis, 2.55), strut_elevation_rad(kThesis, 1.2121));
}

TEST(ChassisGeometry, BendForAxleDistanceInvertsIt) {
  for (double bend = 0.9; bend < 2.7; bend += 0.1) {
    EXPECT_NEAR(bend_for_axle_distance_rad(kThesis, axle_distance_m(kThesis, bend)), bend, 1e-9);
  }
  // Out of reach clamps to the straight configurations.
  EXPECT_DOUBLE_EQ(bend_for_axle_distance_rad(kThesis, 1.0), std::acos(-1.0));
  EXPECT_DOUBLE_EQ(bend_for_axle_distance_rad(kThesis, 0.1), 0.0);
}

TEST(ChassisGeometry, MechanicalStopsContainTheDriverBounds) {
  const BendRange range = mechanical_bend_range(kThesis);
  EXPECT_NEAR(axle_distance_m(kThesis, range.min_rad), kMinAxleDistanceM, 1e-9);
  EXPECT_NEAR(axle_distance_m(kThesis, range.max_rad), kMaxAxleDistanceM, 1e-9);
  EXPECT_LT(range.min_rad, 1.2121);  // (5.3): [1.2121, 2.55]
  EXPECT_GT(range.max_rad, 2.55);
}

TEST(ChassisGeometry, RejectsALeverLongerThanItsStrut) {
  GeometryParams geometry;
  EXPECT_NO_THROW(validate_geometry(geometry));
  geometry.joint_to_exterior_axle_m = 0.5;
  EXPECT_THROW(validate_geometry(geometry), std::invalid_argument);
  geometry = GeometryParams{};
  geometry.wheel_radius_m = 0.0;
  EXPECT_THROW(validate_geometry(geometry), std::invalid_argument);
  geometry = GeometryParams{};
  geometry.track_width_m = 0.1;
  EXPECT_THROW(validate_geometry(geometry), std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::sim
