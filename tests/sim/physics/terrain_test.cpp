#include "sim/physics/terrain.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "../../support/invalid_argument.hpp"

namespace marsokhod::sim {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TerrainSpec read(const std::string& text, const std::filesystem::path& base = ".") {
  const toml::table file = toml::parse(text);
  return terrain_from_toml(*file["terrain"].as_table(), base);
}

// The error must name the key (so that an operator finds it) and say what is wrong.
void expect_error(const std::string& text, const std::string& key, const std::string& what) {
  test_support::expect_invalid_argument([&] { read(text); }, {key, what});
}

TEST(TerrainMaterials, HardGroundGripsAndDoesNotResistRolling) {
  EXPECT_DOUBLE_EQ(hard_ground().sliding_friction, 0.9);
  EXPECT_DOUBLE_EQ(hard_ground().rolling_friction_m, 0.0);
  EXPECT_FALSE(hard_ground().soil.has_value());
}

TEST(TerrainFromToml, FlatHardGroundByDefault) {
  const TerrainSpec terrain = read("[terrain]\nkind = \"flat\"\n");
  EXPECT_EQ(terrain.kind, TerrainKind::kFlat);
  EXPECT_DOUBLE_EQ(terrain.ground.sliding_friction, 0.9);
  EXPECT_TRUE(terrain.obstacles.empty());
}

TEST(TerrainFromToml, NamedAndCustomMaterials) {
  const TerrainSpec custom = read(
      "[terrain]\nkind = \"flat\"\nmaterial = { friction = 0.7, rolling_friction_m = 0.01 }\n");
  EXPECT_DOUBLE_EQ(custom.ground.sliding_friction, 0.7);
  EXPECT_DOUBLE_EQ(custom.ground.torsional_friction_m, 0.0);
  EXPECT_DOUBLE_EQ(custom.ground.rolling_friction_m, 0.01);
  EXPECT_FALSE(custom.ground.soil.has_value());
  EXPECT_TRUE(sand().soil.has_value());  // sand is the soil model's
  // Grass (Field Experiment 5.6): a third more sliding friction than hard ground, a rolling
  // resistance C_rr = 0.01 m / 0.125 m = 0.08 (between a lawn's 0.05 and the 0.16 of the rigid
  // contact sand had before the soil model).
  const TerrainSpec meadow = read("[terrain]\nkind = \"flat\"\nmaterial = \"grass\"\n");
  EXPECT_DOUBLE_EQ(meadow.ground.sliding_friction / hard_ground().sliding_friction, 4.0 / 3.0);
  EXPECT_DOUBLE_EQ(meadow.ground.rolling_friction_m / 0.125, 0.08);
  EXPECT_FALSE(meadow.ground.soil.has_value());
}

// Soft soils put sim/soil under the wheels: Wong's dry sand and the lunar soil.
TEST(TerrainFromToml, SoftSoils) {
  const TerrainSpec sand_terrain =
      read("[terrain]\nkind = \"slope\"\nslope_deg = 10\nmaterial = \"sand\"\n");
  ASSERT_TRUE(sand_terrain.ground.soil.has_value());
  EXPECT_EQ(sand_terrain.ground.soil->name, "sand");
  EXPECT_DOUBLE_EQ(sand_terrain.ground.soil->frictional_modulus, 1528.43e3);
  EXPECT_DOUBLE_EQ(sand_terrain.ground.sliding_friction, 0.5);
  const TerrainSpec lunar = read("[terrain]\nkind = \"flat\"\nmaterial = \"lunar-soil\"\n");
  ASSERT_TRUE(lunar.ground.soil.has_value());
  EXPECT_EQ(lunar.ground.soil->name, "lunar soil");
  // Soft soil on a heightfield too (since 2026-11-29): the soil starts at the image's heights.
  TerrainSpec field;
  field.kind = TerrainKind::kHeightfield;
  field.ground = sand();
  field.heightfield.image.width = 2;
  field.heightfield.image.height = 2;
  field.heightfield.image.values = {0.0, 0.0, 0.0, 0.0};
  EXPECT_NO_THROW(validate(field));
}

// The soil's tangential reload memory (soil_params.hpp) is off unless a soft-soil ground asks for
// it; a hard ground that asks is refused, as is anything but true or false.
TEST(TerrainFromToml, ShearReloadMemoryIsAnOptInOfSoftSoils) {
  const std::string sand = "[terrain]\nkind = \"flat\"\nmaterial = \"sand\"\n";
  EXPECT_FALSE(read(sand).ground.soil->tangential_reload_memory);
  EXPECT_TRUE(read(sand + "shear_reload_memory = true\n").ground.soil->tangential_reload_memory);
  EXPECT_FALSE(
      read(sand + "shear_reload_memory = false\n").ground.soil->tangential_reload_memory);
  expect_error(sand + "shear_reload_memory = 1\n", "terrain.shear_reload_memory",
               "must be true or false");
  expect_error("[terrain]\nkind = \"flat\"\nshear_reload_memory = true\n",
               "terrain.shear_reload_memory", "applies to a soft soil only");
}

TEST(TerrainFromToml, SlopeInDegrees) {
  const TerrainSpec terrain = read("[terrain]\nkind = \"slope\"\nslope_deg = 15\n");
  EXPECT_EQ(terrain.kind, TerrainKind::kSlope);
  EXPECT_NEAR(terrain.slope_rad, 15 * kDeg, 1e-15);
  EXPECT_NEAR(read("[terrain]\nkind = \"slope\"\nslope_deg = -30.5\n").slope_rad, -30.5 * kDeg,
              1e-15);
}

TEST(TerrainFromToml, ObstacleCourseWithARockAndATreeTrunk) {
  const TerrainSpec terrain = read(R"(
[terrain]
kind = "obstacles"
material = "hard"
[[terrain.obstacles]]
shape = "box"
center_m = [1.5, 0.0, 0.05]
size_m = [0.2, 1.0, 0.1]
orientation_deg = [0, 0, 30]
[[terrain.obstacles]]
shape = "cylinder"
center_m = [3.0, 0.0, 0.15]
radius_m = 0.15
length_m = 2.0
orientation_deg = [90, 0, 0]
material = "sand"
)");
  ASSERT_EQ(terrain.obstacles.size(), 2u);
  const Obstacle& rock = terrain.obstacles[0];
  EXPECT_EQ(rock.shape, ObstacleShape::kBox);
  EXPECT_DOUBLE_EQ(rock.box_size_m[1], 1.0);
  EXPECT_NEAR(rock.roll_pitch_yaw_rad[2], 30 * kDeg, 1e-15);
  EXPECT_DOUBLE_EQ(rock.material.sliding_friction, hard_ground().sliding_friction);
  const Obstacle& trunk = terrain.obstacles[1];
  EXPECT_EQ(trunk.shape, ObstacleShape::kCylinder);
  EXPECT_DOUBLE_EQ(trunk.cylinder_radius_m, 0.15);
  EXPECT_DOUBLE_EQ(trunk.cylinder_length_m, 2.0);
  EXPECT_NEAR(trunk.roll_pitch_yaw_rad[0], std::numbers::pi / 2, 1e-15);
  EXPECT_DOUBLE_EQ(trunk.material.sliding_friction, sand().sliding_friction);
}

TEST(TerrainFromToml, HeightfieldImageRelativeToTheScenario) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "marsokhod_terrain_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "dune.pgm") << "P2 3 2 2\n0 1 2\n2 1 0\n";
  const TerrainSpec terrain = read(R"(
[terrain]
kind = "heightfield"
material = "sand"
image = "dune.pgm"
size_m = [6.0, 4.0]
max_height_m = 0.3
)",
                                   dir);
  std::filesystem::remove_all(dir);
  EXPECT_EQ(terrain.kind, TerrainKind::kHeightfield);
  EXPECT_EQ(terrain.heightfield.image.width, 3u);
  EXPECT_DOUBLE_EQ(terrain.heightfield.image.at(0, 2), 1.0);
  EXPECT_DOUBLE_EQ(terrain.heightfield.size_x_m, 6.0);
  EXPECT_DOUBLE_EQ(terrain.heightfield.size_y_m, 4.0);
  EXPECT_DOUBLE_EQ(terrain.heightfield.max_height_m, 0.3);
  EXPECT_TRUE(terrain.ground.soil.has_value());  // soft sand on a heightfield
}

TEST(TerrainFromToml, ErrorsNameTheKey) {
  expect_error("[terrain]\nmaterial = \"hard\"\n", "terrain.kind", "missing");
  expect_error("[terrain]\nkind = \"lava\"\n", "terrain.kind", "\"heightfield\"");
  expect_error("[terrain]\nkind = \"flat\"\nslope_deg = 3\n", "terrain.slope_deg",
               "not a known key");
  expect_error("[terrain]\nkind = \"slope\"\n", "terrain.slope_deg", "missing");
  expect_error("[terrain]\nkind = \"slope\"\nslope_deg = 90\n", "terrain.slope_deg", "outside");
  expect_error("[terrain]\nkind = \"slope\"\nslope_deg = \"steep\"\n", "terrain.slope_deg",
               "number");
  expect_error("[terrain]\nkind = \"flat\"\nmaterial = \"ice\"\n", "terrain.material", "unknown");
  expect_error("[terrain]\nkind = \"flat\"\nmaterial = \"ice\"\n", "terrain.material",
               "\"lunar-soil\"");
  // The rigid contact sand had before the soil model is gone, and so is its skid sinkage.
  expect_error("[terrain]\nkind = \"flat\"\nmaterial = \"rigid-sand\"\n", "terrain.material",
               "\"rigid-sand\", the rigid contact sand had before the soil model, is gone");
  expect_error("[terrain]\nkind = \"flat\"\nmaterial = { friction = 0.5, skid_sinkage = 1.5 }\n",
               "skid_sinkage", "not a known key");
  // The soil model's sand was called "soft-sand" until it became the sand.
  expect_error("[terrain]\nkind = \"flat\"\nmaterial = \"soft-sand\"\n", "terrain.material",
               "\"soft-sand\" is now called \"sand\"");
  expect_error("[terrain]\nkind = \"flat\"\nmaterial = { friction = -1 }\n",
               "terrain.material.friction", "outside");
  expect_error("[terrain]\nkind = \"flat\"\nmaterial = { friction = 1, roll = 1 }\n",
               "terrain.material.roll", "not a known key");
  expect_error("[terrain]\nkind = \"obstacles\"\n", "terrain.obstacles", "at least one");
  expect_error(
      "[terrain]\nkind = \"obstacles\"\n[[terrain.obstacles]]\nshape = \"box\"\n"
      "center_m = [0, 0, 0]\n",
      "terrain.obstacles[0].size_m", "missing");
  expect_error(
      "[terrain]\nkind = \"obstacles\"\n[[terrain.obstacles]]\nshape = \"box\"\n"
      "center_m = [0, 0]\nsize_m = [1, 1, 1]\n",
      "terrain.obstacles[0].center_m", "3 numbers");
  expect_error(
      "[terrain]\nkind = \"heightfield\"\nimage = \"no-such-file.pgm\"\n"
      "size_m = [1, 1]\nmax_height_m = 1\n",
      "terrain.image", "cannot open");
}

TEST(TerrainFromToml, ErrorsGiveTheLine) {
  expect_error("[terrain]\nkind = \"slope\"\n\nslope_deg = 95\n", "line 4", "outside");
}

TEST(TerrainValidate, RejectsWhatMuJoCoCannotBuild) {
  TerrainSpec terrain;
  EXPECT_NO_THROW(validate(terrain));
  terrain.ground.sliding_friction = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(validate(terrain), std::invalid_argument);
  terrain = TerrainSpec{};
  terrain.kind = TerrainKind::kSlope;
  terrain.slope_rad = std::numbers::pi / 2;
  EXPECT_THROW(validate(terrain), std::invalid_argument);
  terrain = TerrainSpec{};
  terrain.kind = TerrainKind::kObstacles;
  EXPECT_THROW(validate(terrain), std::invalid_argument);
  terrain.obstacles.push_back(Obstacle{});
  EXPECT_NO_THROW(validate(terrain));
  terrain.obstacles[0].box_size_m[2] = 0.0;
  EXPECT_THROW(validate(terrain), std::invalid_argument);
  terrain = TerrainSpec{};
  terrain.kind = TerrainKind::kHeightfield;  // no image
  EXPECT_THROW(validate(terrain), std::invalid_argument);
}

TEST(TerrainKindNames, ReadBackAsInTheScenarioFile) {
  EXPECT_EQ(to_string(TerrainKind::kFlat), "flat");
  EXPECT_EQ(to_string(TerrainKind::kSlope), "slope");
  EXPECT_EQ(to_string(TerrainKind::kObstacles), "obstacles");
  EXPECT_EQ(to_string(TerrainKind::kHeightfield), "heightfield");
}

}  // namespace
}  // namespace marsokhod::sim
