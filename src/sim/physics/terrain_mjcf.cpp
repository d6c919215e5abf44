#include "sim/physics/terrain_mjcf.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace marsokhod::sim {
namespace {

// MuJoCo: condim 3 is sliding friction only, 4 adds torsion, 6 adds rolling resistance.
XmlWriter::Attributes material_attributes(const Material& material) {
  int condim = 3;
  if (material.torsional_friction_m > 0.0) condim = 4;
  if (material.rolling_friction_m > 0.0) condim = 6;
  return {{"class", "terrain"},
          {"condim", std::to_string(condim)},
          {"friction", xml_numbers(std::array<double, 3>{material.sliding_friction,
                                                         material.torsional_friction_m,
                                                         material.rolling_friction_m})}};
}

// The ground's tilt: nose-up for +x uphill is a negative rotation about y (right-hand rule).
double ground_pitch_rad(const TerrainSpec& terrain) { return -ground_slope_rad(terrain); }

void write_plane(XmlWriter& xml, const Material& material, const std::array<double, 3>& pos_m,
                 double pitch_rad) {
  XmlWriter::Attributes attributes = material_attributes(material);
  attributes.emplace_back("name", "ground");
  attributes.emplace_back("type", "plane");
  // Soft soil: the wheels (contype 1) pass through the plane, the chassis (contype 3) does not.
  if (material.soil) attributes.emplace_back("conaffinity", "2");
  // The plane is infinite for contacts; the size only bounds how it is drawn.
  attributes.emplace_back("size", "100 100 0.1");
  attributes.emplace_back("pos", xml_numbers(pos_m));
  attributes.emplace_back("quat",
                          xml_numbers(quaternion_from_roll_pitch_yaw({0.0, pitch_rad, 0.0})));
  xml.leaf("geom", attributes);
}

void write_obstacle(XmlWriter& xml, const Obstacle& obstacle, std::size_t index) {
  XmlWriter::Attributes attributes = material_attributes(obstacle.material);
  attributes.emplace_back("name", "obstacle_" + std::to_string(index));
  if (obstacle.shape == ObstacleShape::kBox) {
    attributes.emplace_back("type", "box");
    const std::array<double, 3> half_m{obstacle.box_size_m[0] / 2, obstacle.box_size_m[1] / 2,
                                       obstacle.box_size_m[2] / 2};
    attributes.emplace_back("size", xml_numbers(half_m));
  } else {
    attributes.emplace_back("type", "cylinder");
    attributes.emplace_back("size",
                            xml_numbers(std::array<double, 2>{obstacle.cylinder_radius_m,
                                                              obstacle.cylinder_length_m / 2}));
  }
  attributes.emplace_back("pos", xml_numbers(obstacle.center_m));
  attributes.emplace_back("quat",
                          xml_numbers(quaternion_from_roll_pitch_yaw(obstacle.roll_pitch_yaw_rad)));
  xml.leaf("geom", attributes);
}

// The soil's field (terrain_mjcf.hpp), in the ground's plane: its centre the grid's, its local x
// along the slope (the grid's columns), y across (its rows), its elevation 0 kSoilFieldBelowM
// under the initial level. Like the plane (conaffinity 2), met by the chassis, not the wheels.
void write_soil_field(XmlWriter& xml, const TerrainSpec& terrain) {
  XmlWriter::Attributes attributes = material_attributes(terrain.ground);
  const double slope_rad = ground_slope_rad(terrain);
  const soil::GridSpec& grid = kSoftSoilGrid;
  const double x_m = grid.origin_x_m + 0.5 * grid.cells_x * grid.cell_m;
  const double y_m = grid.origin_y_m + 0.5 * grid.cells_y * grid.cell_m;
  // On the initial surface (z = x·tan α) at the centre, then down its normal (−sin α, 0, cos α).
  const double z_m = x_m * std::tan(slope_rad);
  attributes.emplace_back("name", kSoilFieldName);
  attributes.emplace_back("type", "hfield");
  attributes.emplace_back("hfield", kSoilFieldName);
  attributes.emplace_back("conaffinity", "2");
  attributes.emplace_back("pos", xml_numbers(std::array<double, 3>{
                                     x_m + kSoilFieldBelowM * std::sin(slope_rad), y_m,
                                     z_m - kSoilFieldBelowM * std::cos(slope_rad)}));
  attributes.emplace_back(
      "quat", xml_numbers(quaternion_from_roll_pitch_yaw({0.0, ground_pitch_rad(terrain), 0.0})));
  xml.leaf("geom", attributes);
}

void write_heightfield(XmlWriter& xml, const TerrainSpec& terrain) {
  XmlWriter::Attributes attributes = material_attributes(terrain.ground);
  attributes.emplace_back("name", "heightfield");
  attributes.emplace_back("type", "hfield");
  attributes.emplace_back("hfield", kHeightfieldName);
  // Soft soil: like the plane, met by the chassis only, and under the soil's field.
  if (terrain.ground.soil) {
    attributes.emplace_back("conaffinity", "2");
    attributes.emplace_back("pos", xml_numbers(std::array<double, 3>{0.0, 0.0, -kSoilFieldBelowM}));
  }
  xml.leaf("geom", attributes);
}

}  // namespace

double ground_level_m(const TerrainSpec& terrain, double x_m, double y_m) {
  if (terrain.kind != TerrainKind::kHeightfield) return x_m * std::tan(ground_slope_rad(terrain));
  const Heightfield& field = terrain.heightfield;
  const GrayImage& image = field.image;
  // In pixels from the field's (−x, −y) corner: column c at x = −size_x/2 + c·size_x/(width − 1).
  const double column =
      (x_m + 0.5 * field.size_x_m) / field.size_x_m * static_cast<double>(image.width - 1);
  const double row =
      (y_m + 0.5 * field.size_y_m) / field.size_y_m * static_cast<double>(image.height - 1);
  if (!(column >= 0.0 && row >= 0.0 && column <= static_cast<double>(image.width - 1) &&
        row <= static_cast<double>(image.height - 1))) {
    return -kHeightfieldSurroundDropM;
  }
  const auto c0 = std::min(static_cast<std::size_t>(column), image.width - 2);
  const auto r0 = std::min(static_cast<std::size_t>(row), image.height - 2);
  const double u = column - static_cast<double>(c0), v = row - static_cast<double>(r0);
  // MuJoCo's row r is the image's row height − 1 − r (copy_heightfield, mujoco_model.cpp).
  const auto at = [&](std::size_t r, std::size_t c) { return image.at(image.height - 1 - r, c); };
  const double value = (1.0 - v) * ((1.0 - u) * at(r0, c0) + u * at(r0, c0 + 1)) +
                       v * ((1.0 - u) * at(r0 + 1, c0) + u * at(r0 + 1, c0 + 1));
  return value * field.max_height_m;
}

std::array<double, 4> quaternion_from_roll_pitch_yaw(const std::array<double, 3>& rpy_rad) {
  const double cr = std::cos(rpy_rad[0] / 2), sr = std::sin(rpy_rad[0] / 2);
  const double cp = std::cos(rpy_rad[1] / 2), sp = std::sin(rpy_rad[1] / 2);
  const double cy = std::cos(rpy_rad[2] / 2), sy = std::sin(rpy_rad[2] / 2);
  return {cr * cp * cy + sr * sp * sy, sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
          cr * cp * sy - sr * sp * cy};
}

void write_terrain_assets(XmlWriter& xml, const TerrainSpec& terrain) {
  if (terrain.ground.soil) {
    // Vertices at the cells' centres: (cells − 1) cells apart, measured along the slope.
    const soil::GridSpec& grid = kSoftSoilGrid;
    const double slope_rad = ground_slope_rad(terrain);
    xml.leaf("hfield",
             {{"name", kSoilFieldName},
              {"nrow", std::to_string(grid.cells_y)},
              {"ncol", std::to_string(grid.cells_x)},
              {"size", xml_numbers(std::array<double, 4>{
                           0.5 * (grid.cells_x - 1) * grid.cell_m / std::cos(slope_rad),
                           0.5 * (grid.cells_y - 1) * grid.cell_m,
                           kSoilFieldBelowM + soil_field_above_m(terrain), kSoilFieldBaseM})}});
  }
  if (terrain.kind != TerrainKind::kHeightfield) return;
  const Heightfield& field = terrain.heightfield;
  xml.leaf("hfield",
           {{"name", kHeightfieldName},
            {"nrow", std::to_string(field.image.height)},
            {"ncol", std::to_string(field.image.width)},
            {"size", xml_numbers(std::array<double, 4>{field.size_x_m / 2, field.size_y_m / 2,
                                                       field.max_height_m, kHeightfieldBaseM})}});
}

void write_terrain_geoms(XmlWriter& xml, const TerrainSpec& terrain) {
  switch (terrain.kind) {
    case TerrainKind::kFlat:
    case TerrainKind::kObstacles:
    case TerrainKind::kSlope: {
      // On soft soil the plane lies kSoilFieldBelowM down its normal, under the soil's field.
      const double drop_m = terrain.ground.soil ? kSoilFieldBelowM : 0.0;
      const double pitch_rad = ground_pitch_rad(terrain);
      write_plane(xml, terrain.ground,
                  {-drop_m * std::sin(pitch_rad), 0.0, -drop_m * std::cos(pitch_rad)}, pitch_rad);
      if (terrain.ground.soil) write_soil_field(xml, terrain);
      break;
    }
    case TerrainKind::kHeightfield: {
      const double drop_m = terrain.ground.soil ? kSoilFieldBelowM : 0.0;
      write_heightfield(xml, terrain);
      write_plane(xml, terrain.ground, {0.0, 0.0, -kHeightfieldSurroundDropM - drop_m}, 0.0);
      if (terrain.ground.soil) write_soil_field(xml, terrain);
      break;
    }
  }
  for (std::size_t i = 0; i < terrain.obstacles.size(); ++i) {
    write_obstacle(xml, terrain.obstacles[i], i);
  }
}

}  // namespace marsokhod::sim
