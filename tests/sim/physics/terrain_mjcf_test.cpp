#include "sim/physics/terrain_mjcf.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace marsokhod::sim {
namespace {

// Rotates v by the unit quaternion q = (w, x, y, z).
std::array<double, 3> rotate(const std::array<double, 4>& q, const std::array<double, 3>& v) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return {
      (1 - 2 * (y * y + z * z)) * v[0] + 2 * (x * y - w * z) * v[1] + 2 * (x * z + w * y) * v[2],
      2 * (x * y + w * z) * v[0] + (1 - 2 * (x * x + z * z)) * v[1] + 2 * (y * z - w * x) * v[2],
      2 * (x * z - w * y) * v[0] + 2 * (y * z + w * x) * v[1] + (1 - 2 * (x * x + y * y)) * v[2]};
}

void expect_near(const std::array<double, 3>& actual, const std::array<double, 3>& expected) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(actual[i], expected[i], 1e-12) << "component " << i;
}

TEST(QuaternionFromRollPitchYaw, EachAxisByTheRightHandRule) {
  const double quarter = std::numbers::pi / 2;
  expect_near(rotate(quaternion_from_roll_pitch_yaw({0, 0, quarter}), {1, 0, 0}), {0, 1, 0});
  expect_near(rotate(quaternion_from_roll_pitch_yaw({quarter, 0, 0}), {0, 0, 1}), {0, -1, 0});
  expect_near(rotate(quaternion_from_roll_pitch_yaw({0, quarter, 0}), {1, 0, 0}), {0, 0, -1});
}

TEST(QuaternionFromRollPitchYaw, RollFirstThenPitchThenYaw) {
  // R = Rz·Ry·Rx: a trunk's axis (z) rolled onto −y, then yawed by 90° onto +x.
  const double quarter = std::numbers::pi / 2;
  expect_near(rotate(quaternion_from_roll_pitch_yaw({quarter, 0, quarter}), {0, 0, 1}), {1, 0, 0});
}

std::string geoms_of(const TerrainSpec& terrain) {
  XmlWriter xml;
  write_terrain_geoms(xml, terrain);
  return xml.text();
}

TEST(TerrainMjcf, MaterialsSelectTheContactDimension) {
  TerrainSpec terrain;
  EXPECT_NE(geoms_of(terrain).find("condim=\"3\" friction=\"0.9 0 0\""), std::string::npos);
  terrain.ground = Material{0.5, 0.0, 0.02};  // rolling friction
  EXPECT_NE(geoms_of(terrain).find("condim=\"6\" friction=\"0.5 0 0.02\""), std::string::npos);
  terrain.ground = Material{0.8, 0.01, 0.0};
  EXPECT_NE(geoms_of(terrain).find("condim=\"4\""), std::string::npos);
}

TEST(TerrainMjcf, ASlopeTiltsTheGroundNoseUp) {
  TerrainSpec terrain;
  terrain.kind = TerrainKind::kSlope;
  terrain.slope_rad = 0.3;
  const std::string xml = geoms_of(terrain);
  const auto q = quaternion_from_roll_pitch_yaw({0, -0.3, 0});
  EXPECT_NE(xml.find("quat=\"" + xml_numbers(q) + "\""), std::string::npos) << xml;
  // Uphill for +x: the plane's normal leans back, toward −x.
  EXPECT_LT(rotate(q, {0, 0, 1})[0], 0.0);
}

TEST(TerrainMjcf, ObstaclesAreHalfSizedForMuJoCo) {
  TerrainSpec terrain;
  terrain.kind = TerrainKind::kObstacles;
  Obstacle rock;
  rock.box_size_m = {0.2, 1.0, 0.1};
  Obstacle trunk;
  trunk.shape = ObstacleShape::kCylinder;
  trunk.cylinder_radius_m = 0.15;
  trunk.cylinder_length_m = 2.0;
  terrain.obstacles = {rock, trunk};
  const std::string xml = geoms_of(terrain);
  EXPECT_NE(xml.find("name=\"obstacle_0\" type=\"box\" size=\"0.1 0.5 0.05\""), std::string::npos)
      << xml;
  EXPECT_NE(xml.find("name=\"obstacle_1\" type=\"cylinder\" size=\"0.15 1\""), std::string::npos)
      << xml;
}

TEST(TerrainMjcf, HeightfieldAssetSpansTheImage) {
  TerrainSpec terrain;
  terrain.kind = TerrainKind::kHeightfield;
  terrain.heightfield.image = GrayImage{4, 3, std::vector<double>(12, 0.0)};
  terrain.heightfield.size_x_m = 8.0;
  terrain.heightfield.size_y_m = 6.0;
  terrain.heightfield.max_height_m = 0.5;
  XmlWriter xml;
  write_terrain_assets(xml, terrain);
  EXPECT_NE(xml.text().find("nrow=\"3\" ncol=\"4\" size=\"4 3 0.5 0.1\""), std::string::npos)
      << xml.text();
  EXPECT_NE(geoms_of(terrain).find("type=\"hfield\""), std::string::npos);
}

}  // namespace
}  // namespace marsokhod::sim
