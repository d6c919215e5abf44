#include "sim/physics/mujoco_model.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "sim/physics/terrain_mjcf.hpp"

namespace marsokhod::sim {
namespace {

TEST(LoadMjcf, CompilesFromMemory) {
  const ModelPtr model = load_mjcf(
      "<mujoco><worldbody><body><freejoint/><geom size=\"0.1\"/></body></worldbody></mujoco>");
  ASSERT_NE(model, nullptr);
  EXPECT_EQ(model->nbody, 2);
}

TEST(LoadMjcf, MuJoCosErrorReachesTheCaller) {
  try {
    load_mjcf("<mujoco><worldbody><geom type=\"banana\"/></worldbody></mujoco>");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("banana"), std::string::npos) << e.what();
  }
}

TEST(RequireId, NamesWhatIsMissing) {
  const ModelPtr model = load_mjcf(
      "<mujoco><worldbody><body name=\"b\"><geom size=\"1\"/></body>"
      "</worldbody></mujoco>");
  EXPECT_EQ(require_id(*model, mjOBJ_BODY, "b"), 1);
  EXPECT_THROW(require_id(*model, mjOBJ_BODY, "c"), std::logic_error);
}

// A ray straight down onto the terrain only (geom group 0).
double ground_height_m(const mjModel& model, double x_m, double y_m) {
  const DataPtr data(mj_makeData(&model));
  mj_forward(&model, data.get());
  const mjtNum start[3] = {x_m, y_m, 10.0};
  const mjtNum down[3] = {0.0, 0.0, -1.0};
  const mjtByte terrain_only[mjNGROUP] = {1, 0, 0, 0, 0, 0};
  int geom = -1;
  return 10.0 - mj_ray(&model, data.get(), start, down, terrain_only, 1, -1, &geom);
}

TEST(LoadRoverModel, HeightfieldTopRowLiesAtPlusY) {
  TerrainSpec terrain;
  terrain.kind = TerrainKind::kHeightfield;
  // A map: the top row white (a ridge at the north edge), one grey pixel at the south-east.
  terrain.heightfield.image = GrayImage{4, 3, {1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0.5}};
  terrain.heightfield.size_x_m = 4.0;
  terrain.heightfield.size_y_m = 2.0;
  terrain.heightfield.max_height_m = 0.4;
  const ModelPtr model = load_rover_model(Params{}, terrain, 0.001);
  EXPECT_NEAR(ground_height_m(*model, -1.999, 0.999), 0.4, 2e-3);
  EXPECT_NEAR(ground_height_m(*model, 1.999, 0.999), 0.4, 2e-3);
  EXPECT_NEAR(ground_height_m(*model, 0.0, 0.0), 0.0, 1e-9);
  EXPECT_NEAR(ground_height_m(*model, 1.999, -0.999), 0.2, 2e-3);
  EXPECT_NEAR(ground_height_m(*model, -1.999, -0.999), 0.0, 1e-9);
  // Beyond the image the surrounding plane, just below height 0.
  EXPECT_NEAR(ground_height_m(*model, 5.0, 0.0), -kHeightfieldSurroundDropM, 1e-9);
}

}  // namespace
}  // namespace marsokhod::sim
