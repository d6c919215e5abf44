// The ground the simulated rover drives on: flat, a slope, an obstacle course or a heightfield,
// each with a material. A scenario file describes it in its [terrain] table (terrain_from_toml).
//
// World frame: x forward from the rover's start, y left, z up; the rover starts with the center of
// its center axle above the origin, facing +x.
#pragma once

#include <toml++/toml.h>

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sim/physics/pgm_image.hpp"
#include "sim/soil/soil_params.hpp"

namespace marsokhod::sim {

// Contact properties of a ground material, as MuJoCo's three friction coefficients.
// MuJoCo combines the two geoms of a contact by the larger coefficient; the rover's own geoms carry
// near-zero friction, so the ground's material alone decides.
//
// Rolling resistance is MuJoCo's rolling friction (contact dimension 6): a torque opposing the
// wheel's rolling, at most rolling_friction_m · normal force. It is a resistance coefficient
// C_rr times the wheel radius: C_rr = 0.16 on r = 0.125 m gives 0.02 m. Chosen over a
// speed-proportional wheel damping because sand resists a slowly rolling wheel as much as a fast
// one, and because it acts at the contact (a lifted wheel spins freely). (Sand itself is the soil
// model since issue #14: the rigid contact sand had before — μ 0.5, this rolling friction and a
// "skid sinkage" that raised a skidding wheel's friction — is gone since 2026-11-29.)
struct Material {
  double sliding_friction = 0.9;      // μ, Coulomb friction along the ground
  double torsional_friction_m = 0.0;  // resistance to spinning about the contact normal
  double rolling_friction_m = 0.0;    // rolling resistance (see above); > 0 selects condim 6
  // Soft soil (sim/soil): the wheels do not touch this ground in MuJoCo; the soil model's forces
  // act on them instead (rover_soft_soil.cpp). The chassis still meets it with the friction above.
  // Ground of any kind (on a heightfield the soil starts at the image's heights); an obstacle
  // ignores it (obstacles are rigid).
  std::optional<soil::SoilParams> soil = std::nullopt;
};

// Hard ground (carpet-covered wheels on a lab floor, packed soil, rock): μ ≈ 0.9, no rolling loss,
// no sinkage.
Material hard_ground();
// Grass (Field Experiment 5.6, the unmown meadow: "Turning the robot on grass was stressful; the
// blades of the wheels were retained by the stems", while the rolking modes "were tested
// successfully"): μ = 1.2, a third above hard ground, for a bladed wheel dragged across the turf
// shears or bends the stems caught between its blades on top of the rim's Coulomb friction; a
// rolling wheel lifts its blades out of the stems and meets only a rolling resistance
// C_rr = 0.08 (0.01 m on the 0.125 m wheel: a rigid wheel on a meadow, between a lawn's 0.05 and
// the rigid contact sand had before the soil model, 0.16); nothing is ploughed. Skid
// steering turns by dragging the exterior wheels sideways, so a spin meets μ·N at every wheel
// that slides (a third more torque, a third more power), while driving straight rolls.
Material grass();
// Soft soils, the soil model of sim/soil under the wheels (soil_params.hpp), μ = 0.5 for the
// chassis: sand is Wong's dry sand; the lunar soil is Ding et al.'s.
Material sand();
Material soft_lunar_soil();
// The material of a terrain file's name: "hard", "sand", "grass" or "lunar-soil";
// nullopt for another name.
std::optional<Material> material_named(std::string_view name);
// For a name material_named refuses: what became of it, as " (…)" to append to the refusal —
// "soft-sand" is now "sand", "rigid-sand" is gone — or "" for any other name.
std::string retired_material_note(std::string_view name);

enum class TerrainKind { kFlat, kSlope, kObstacles, kHeightfield };

enum class ObstacleShape { kBox, kCylinder };

// A fixed rigid obstacle: a rock (box) or a tree trunk (cylinder).
struct Obstacle {
  ObstacleShape shape = ObstacleShape::kBox;
  std::array<double, 3> center_m{};
  std::array<double, 3> box_size_m{0.1, 0.1, 0.1};  // box: full extents along its own x, y, z
  double cylinder_radius_m = 0.1;                   // cylinder: its axis is its own z
  double cylinder_length_m = 1.0;
  // Orientation as roll about x, then pitch about y, then yaw about z (R = Rz·Ry·Rx): a trunk
  // lying across the rover's path is a cylinder with roll = π/2.
  std::array<double, 3> roll_pitch_yaw_rad{};
  Material material = hard_ground();
};

// A grey-scale image as ground elevation: black is height 0, white max_height_m. The image
// spans size_x_m along x (its columns, left to right) and size_y_m along y (its rows, the top row
// at +y, as on a map), centered on the origin. Around it the ground is flat, 1 cm below black.
struct Heightfield {
  GrayImage image;
  double size_x_m = 10.0;
  double size_y_m = 10.0;
  double max_height_m = 0.5;
};

struct TerrainSpec {
  TerrainKind kind = TerrainKind::kFlat;
  Material ground = hard_ground();
  // kSlope: the ground's pitch about the world y-axis through the origin; positive is uphill for
  // a rover driving +x (the ground's height is x·tan(slope_rad)). Within (−π/2, π/2).
  double slope_rad = 0.0;
  // Obstacles stand on the ground of any kind; kObstacles is flat ground with at least one.
  std::vector<Obstacle> obstacles;
  Heightfield heightfield;  // kHeightfield only
};

// Throws std::invalid_argument naming the first field that cannot be built (non-finite numbers,
// non-positive sizes, a slope of ±90°, an empty heightfield, a negative friction).
void validate(const TerrainSpec& terrain);

// Reads the [terrain] table of a scenario file. Relative image paths are taken from base_dir
// (the scenario file's folder). Throws std::invalid_argument naming the key, its line and what
// is allowed. The keys (angles in degrees, lengths in metres):
//
//   kind = "flat" | "slope" | "obstacles" | "heightfield"
//   material = "hard" | "sand" | "grass" | "lunar-soil"
//            | { friction = 0.7, torsional_friction_m = 0.0,
//                                  rolling_friction_m = 0.01 }           # optional, "hard"
//   shear_reload_memory = true             # a soft soil only; optional, false (soil_params.hpp)
//   slope_deg = 15.0                       # kind = "slope": + is uphill driving +x
//   image = "dunes.pgm"                    # kind = "heightfield": a P2/P5 PGM
//   size_m = [8.0, 6.0]                    #   its extent along x (columns) and y (rows)
//   max_height_m = 0.4                     #   the height of a white pixel
//   [[terrain.obstacles]]                  # any kind; at least one for kind = "obstacles"
//   shape = "box" | "cylinder"
//   center_m = [1.5, 0.0, 0.05]
//   size_m = [0.2, 1.0, 0.1]               # box: full extents
//   radius_m = 0.15                        # cylinder
//   length_m = 2.0                         # cylinder, along its own z
//   orientation_deg = [90.0, 0.0, 0.0]     # roll, pitch, yaw; optional
//   material = "hard"                      # optional, the ground's material
TerrainSpec terrain_from_toml(const toml::table& terrain_table,
                              const std::filesystem::path& base_dir);

std::string to_string(TerrainKind kind);

}  // namespace marsokhod::sim
