// The terrain part of the generated MJCF: a ground plane (flat or tilted), obstacles, a
// heightfield. Terrain geoms are group 0, contype 0 / conaffinity 1: they touch the rover (contype
// 1, conaffinity 0) but neither each other nor does the rover touch itself.
#pragma once

#include <array>

#include "sim/physics/terrain.hpp"
#include "sim/physics/xml_writer.hpp"
#include "sim/soil/soil_grid.hpp"

namespace marsokhod::sim {

inline constexpr const char* kHeightfieldName = "terrain";
// Under and around a heightfield the ground is a plane this far below the image's black (height
// 0), so that it neither doubles the heightfield's contacts nor leaves a cliff at its edge.
inline constexpr double kHeightfieldSurroundDropM = 0.01;
inline constexpr double kHeightfieldBaseM = 0.1;  // the heightfield's thickness below height 0

// Soft soil (rover_soft_soil.cpp): the soil's grid, 2 cm cells from x = −3 m to 9 m and y = −3 m
// to 3 m around the start, and a MuJoCo height field with a vertex at each cell's centre that
// copies the grid's surface, so that the chassis meets the ruts and heaps the wheels leave (the
// wheels themselves pass through it; the soil model carries them). The field spans the soil from
// kSoilFieldBelowM under the ground's plane (z = 0, or x·tan α on a slope) to soil_field_above_m
// over it, along the plane's normal: kSoilFieldAboveM over the ground's initial level, and on a
// heightfield over its highest point (its white). The ground itself — the plane, or the
// heightfield and the plane around it — lies kSoilFieldBelowM lower than it would on rigid
// ground, so that under the grid only the field is met and beyond it the chassis still finds
// ground.
inline constexpr soil::GridSpec kSoftSoilGrid{-3.0, -3.0, 0.02, 600, 300};
inline constexpr const char* kSoilFieldName = "soil";
inline constexpr double kSoilFieldBelowM = 0.25;  // deeper than a wheel's radius: any hole it digs
inline constexpr double kSoilFieldAboveM = 0.15;  // rims and spoil; under the centre unit's belly
inline constexpr double kSoilFieldBaseM = 0.05;   // the field's thickness under its lowest level

// The ground's slope α: the terrain's on a slope, 0 on flat and obstacle ground.
inline double ground_slope_rad(const TerrainSpec& terrain) {
  return terrain.kind == TerrainKind::kSlope ? terrain.slope_rad : 0.0;
}
// The ground's initial level under (x, y), world z: 0 on flat and obstacle ground, x·tan α on a
// slope; on a heightfield its image's height, bilinear between the image's pixels as MuJoCo lays
// them out (the field centred on the origin, its rows from −y up, the image's top row at +y;
// MuJoCo's own triangles depart from it by under the image's curvature), and beyond its edges the
// plane around it, kHeightfieldSurroundDropM down. Soft soil starts at this level.
double ground_level_m(const TerrainSpec& terrain, double x_m, double y_m);
// How far the soil's field reaches above the ground's plane: kSoilFieldAboveM over the ground's
// highest initial level (0 on a plane, a heightfield's max_height_m).
inline double soil_field_above_m(const TerrainSpec& terrain) {
  return kSoilFieldAboveM +
         (terrain.kind == TerrainKind::kHeightfield ? terrain.heightfield.max_height_m : 0.0);
}
// A vertex's datum in the soil's field for a rise (along the ground's normal) over the ground's
// plane: its share of the field's range, kSoilFieldBelowM below to above_m above, clamped to it.
inline float soil_field_elevation(double rise_m, double above_m) {
  const double share = (rise_m + kSoilFieldBelowM) / (kSoilFieldBelowM + above_m);
  return static_cast<float>(share < 0.0 ? 0.0 : (share > 1.0 ? 1.0 : share));
}

// A quaternion (w, x, y, z) of R = Rz(yaw)·Ry(pitch)·Rx(roll).
std::array<double, 4> quaternion_from_roll_pitch_yaw(const std::array<double, 3>& rpy_rad);

// The <asset> children (the heightfield's grid size), if any.
void write_terrain_assets(XmlWriter& xml, const TerrainSpec& terrain);
// The <worldbody> geoms of the ground and the obstacles.
void write_terrain_geoms(XmlWriter& xml, const TerrainSpec& terrain);

}  // namespace marsokhod::sim
