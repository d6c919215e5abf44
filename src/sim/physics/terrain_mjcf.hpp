// The terrain part of the generated MJCF: a ground plane (flat or tilted), obstacles, a
// heightfield. Terrain geoms are group 0, contype 0 / conaffinity 1: they touch the rover (contype
// 1, conaffinity 0) but neither each other nor does the rover touch itself.
#pragma once

#include <array>

#include "sim/physics/terrain.hpp"
#include "sim/physics/xml_writer.hpp"

namespace marsokhod::sim {

inline constexpr const char* kHeightfieldName = "terrain";
// Under and around a heightfield the ground is a plane this far below the image's black (height
// 0), so that it neither doubles the heightfield's contacts nor leaves a cliff at its edge.
inline constexpr double kHeightfieldSurroundDropM = 0.01;
inline constexpr double kHeightfieldBaseM = 0.1;  // the heightfield's thickness below height 0

// A quaternion (w, x, y, z) of R = Rz(yaw)·Ry(pitch)·Rx(roll).
std::array<double, 4> quaternion_from_roll_pitch_yaw(const std::array<double, 3>& rpy_rad);

// The <asset> children (the heightfield's grid size), if any.
void write_terrain_assets(XmlWriter& xml, const TerrainSpec& terrain);
// The <worldbody> geoms of the ground and the obstacles.
void write_terrain_geoms(XmlWriter& xml, const TerrainSpec& terrain);

}  // namespace marsokhod::sim
