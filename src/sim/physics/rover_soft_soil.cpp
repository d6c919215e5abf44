// Soft soil under the wheels (terrain.hpp: a ground material with `soil`, sim/soil). The wheels
// pass through the ground plane (contact bits, rover_mjcf.cpp); each step, before MuJoCo's, every
// wheel's centre, axle, velocity and spin go to the soil model and its force and torque come back
// as xfrc_applied on the wheel body, the torque moved from the wheel's centre to its centre of
// mass. The kinematics are those MuJoCo computed at the start of the last step, one step (1 ms)
// old.
//
// The grid (kSoftSoilGrid, terrain_mjcf.hpp): a window of 2 cm cells, 12 m by 6 m, from x = −3 m
// to 9 m and y = −3 m to 3 m around the start, at the ground's initial level (ground_level_m:
// flat, x·tan(slope) on a slope, a heightfield's image). It follows the rover: when the chassis comes within kSoilWindowMarginM of an edge,
// the window moves by whole cells to put the chassis back at its middle along that axis
// (SoilGrid::shift: the ground it takes in is undisturbed, the ruts it leaves behind are
// forgotten but for the books), and the height field's geom moves with it. Beyond the window the
// edge cells' heights continue. Each time the grid yields (every 10 ms, SoftSoil) the cells that
// changed are copied into the MuJoCo height field the chassis meets (terrain_mjcf.hpp).
// Blades: mirror-symmetric across the rover's middle — the left wheels right-handed, the right
// wheels left-handed (docs/simulator.md), inclined at the geometry's blade_inclination_rad (i);
// rim radius = wheel radius − 1 cm of blade.
#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/physics/chassis_geometry.hpp"
#include "sim/physics/rover_mjcf.hpp"
#include "sim/physics/rover_physics_impl.hpp"
#include "sim/physics/terrain_mjcf.hpp"

namespace marsokhod::sim {
namespace {

using soil::operator+;
using soil::operator-;

constexpr double kBladeHeightM = 0.010;  // chapter 3.1: 0.125 m with blades, 0.115 on granules
// The field is met while the chassis comes this close to the soil (update_soil_field).
constexpr double kSoilFieldReachM = 0.02;
// A wheel whose contact is switched off (set_wheel_contact) is shown to the soil this high up.
constexpr double kLiftedM = 10.0;
// The soil's window moves when the chassis comes this close to its edge: more than the rover's
// half length (0.66 m with the joints extended) and the cells its spoil and the repose around a
// wheel reach (≈ 0.2 m), so that no wheel meets the window's edge.
constexpr double kSoilWindowMarginM = 1.5;

bool is_left_wheel(std::size_t wheel) {
  return wheel == kFrontLeft || wheel == kCenterLeft || wheel == kBackLeft;
}

}  // namespace

void RoverPhysics::Impl::build_soft_soil(const TerrainSpec& terrain) {
  if (!terrain.ground.soil) return;
  std::vector<soil::WheelGeometry> wheels(kWheelCount);
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    wheels[wheel].rim_radius_m = params.geometry.wheel_radius_m - kBladeHeightM;
    wheels[wheel].blade_height_m = kBladeHeightM;
    wheels[wheel].blade_inclination_rad = params.geometry.blade_inclination_rad;
    wheels[wheel].width_m = kWheelWidthM;
    wheels[wheel].handedness =
        is_left_wheel(wheel) ? soil::BladeHandedness::kRight : soil::BladeHandedness::kLeft;
  }
  const double slope_rad = ground_slope_rad(terrain);
  const double slope = std::tan(slope_rad);
  soft_soil.emplace(
      *terrain.ground.soil, kSoftSoilGrid,
      [terrain](double x_m, double y_m) { return ground_level_m(terrain, x_m, y_m); }, wheels);
  soil_field = require_id(*model, mjOBJ_HFIELD, kSoilFieldName);
  soil_field_geom = require_id(*model, mjOBJ_GEOM, kSoilFieldName);
  soil_field_cos = std::cos(slope_rad);
  soil_field_slope = slope;
  soil_field_above = soil_field_above_m(terrain);
  place_soil_field_plane();
  soil_field_normal = {-std::sin(slope_rad), 0.0, std::cos(slope_rad)};
  for (int geom = 0; geom < model->ngeom; ++geom) {
    if (model->geom_bodyid[geom] != 0 && (model->geom_contype[geom] & 2) != 0) {
      soil_field_geoms.push_back(geom);
    }
  }
  // The model was built with the field at the ground's plane (mujoco_model.cpp); the soil's
  // initial level goes in now (no rise on a plane, a heightfield's relief).
  copy_soil_to_field();
}

// The ground's plane under each column of the window's cells.
void RoverPhysics::Impl::place_soil_field_plane() {
  const soil::GridSpec& spec = soft_soil->grid().spec();
  soil_field_plane.resize(static_cast<std::size_t>(spec.cells_x));
  for (int ix = 0; ix < spec.cells_x; ++ix) {
    soil_field_plane[static_cast<std::size_t>(ix)] =
        (spec.origin_x_m + (ix + 0.5) * spec.cell_m) * soil_field_slope;
  }
}

// The window's move (the file's header): by whole cells along each axis on which the chassis has
// come within kSoilWindowMarginM of an edge, to the window's middle; the field's geom moves along
// the ground's plane with it, and takes the whole window again.
void RoverPhysics::Impl::follow_with_soil_window() {
  soil::SoilGrid& grid = soft_soil->grid();
  const soil::GridSpec& spec = grid.spec();
  const auto cells_to_middle = [&](double at_m, double origin_m, int cells) {
    const double span_m = cells * spec.cell_m;
    if (at_m - origin_m >= kSoilWindowMarginM && origin_m + span_m - at_m >= kSoilWindowMarginM) {
      return 0;
    }
    return static_cast<int>(std::lround((at_m - (origin_m + 0.5 * span_m)) / spec.cell_m));
  };
  const double x_m = data->qpos[ids.free_qpos], y_m = data->qpos[ids.free_qpos + 1];
  const int dx = cells_to_middle(x_m, spec.origin_x_m, spec.cells_x);
  const int dy = cells_to_middle(y_m, spec.origin_y_m, spec.cells_y);
  if (dx == 0 && dy == 0) return;
  grid.shift(dx, dy);
  mjtNum* pos = model->geom_pos + 3 * soil_field_geom;
  pos[0] += dx * spec.cell_m;
  pos[1] += dy * spec.cell_m;
  pos[2] += dx * spec.cell_m * soil_field_slope;
  place_soil_field_plane();
  update_soil_field();
}

// Elevation of a vertex: the cell's rise δ over the ground's plane (its initial level, x·tan α),
// vertical in the grid, along the plane's normal in the field (×cos α; the vertex keeps its
// place in the plane, δ·sin α·cos α downhill of the soil it stands for — under a millimetre for a
// 5 cm rut on 1°, 8.6 mm on 10°), over the field's range from kSoilFieldBelowM below to
// soil_field_above_m above (clamped to it).
void RoverPhysics::Impl::copy_soil_to_field() {
  soil::SoilGrid& grid = soft_soil->grid();
  const soil::CellBox box = grid.changed();
  if (box.empty()) return;
  const mjModel& m = *model;
  const int columns = m.hfield_ncol[soil_field];
  float* field = m.hfield_data + m.hfield_adr[soil_field];
  for (int iy = box.min_y; iy <= box.max_y; ++iy) {
    for (int ix = box.min_x; ix <= box.max_x; ++ix) {
      const double rise =
          (grid.cell_surface_m(ix, iy) - soil_field_plane[static_cast<std::size_t>(ix)]) *
          soil_field_cos;
      field[iy * columns + ix] = soil_field_elevation(rise, soil_field_above);
    }
  }
  grid.clear_changed();
}

// Whether any geom the field can meet comes within kSoilFieldReachM of the soil under it: its
// lowest point along the ground's normal n (its support point in the direction −n) against the
// highest soil, along n, under its box in x and y. Shapes as MuJoCo's: a capsule's or cylinder's
// radius and half-length along its local z, a box's half-sizes; any other its bounding sphere.
bool RoverPhysics::Impl::chassis_near_soil() const {
  const mjModel& m = *model;
  const mjData& d = *data;
  const soil::SoilGrid& grid = soft_soil->grid();
  const soil::GridSpec& spec = grid.spec();
  const std::array<double, 3>& n = soil_field_normal;
  const auto cell = [&](double at_m, double origin_m, int count) {
    return std::clamp(static_cast<int>(std::floor((at_m - origin_m) / spec.cell_m)), 0,
                      count - 1);
  };
  for (int geom : soil_field_geoms) {
    const mjtNum* p = d.geom_xpos + 3 * geom;
    const mjtNum* r = d.geom_xmat + 9 * geom;  // row-major: column k is the geom's axis k
    const mjtNum* size = m.geom_size + 3 * geom;
    const auto along = [&](const std::array<double, 3>& u, int axis) {  // |u·axis|
      return std::abs(u[0] * r[axis] + u[1] * r[3 + axis] + u[2] * r[6 + axis]);
    };
    const auto reach = [&](const std::array<double, 3>& u) {  // support of the geom along ±u
      switch (m.geom_type[geom]) {
        case mjGEOM_SPHERE:
          return size[0];
        case mjGEOM_CAPSULE:
          return size[1] * along(u, 2) + size[0];
        case mjGEOM_CYLINDER: {
          const double axial = along(u, 2);
          return size[1] * axial + size[0] * std::sqrt(std::max(1.0 - axial * axial, 0.0));
        }
        case mjGEOM_BOX:
          return size[0] * along(u, 0) + size[1] * along(u, 1) + size[2] * along(u, 2);
        default:
          return m.geom_rbound[geom];
      }
    };
    const double lowest = n[0] * p[0] + n[1] * p[1] + n[2] * p[2] - reach(n);
    // Above the field's top (its elevations end soil_field_above over the plane): out of reach.
    if (lowest > soil_field_above + kSoilFieldReachM) continue;
    const double half_x = reach({1.0, 0.0, 0.0}), half_y = reach({0.0, 1.0, 0.0});
    const int x0 = cell(p[0] - half_x, spec.origin_x_m, spec.cells_x);
    const int x1 = cell(p[0] + half_x, spec.origin_x_m, spec.cells_x);
    const int y0 = cell(p[1] - half_y, spec.origin_y_m, spec.cells_y);
    const int y1 = cell(p[1] + half_y, spec.origin_y_m, spec.cells_y);
    double highest = -std::numeric_limits<double>::infinity();  // rise over the plane, vertical
    for (int iy = y0; iy <= y1; ++iy) {
      for (int ix = x0; ix <= x1; ++ix) {
        highest = std::max(highest, grid.cell_surface_m(ix, iy) -
                                        soil_field_plane[static_cast<std::size_t>(ix)]);
      }
    }
    if (lowest - std::min(highest, soil_field_above) * soil_field_cos <= kSoilFieldReachM) {
      return true;
    }
  }
  return false;
}

// Each time the grid yields (10 ms), and when the rover is set down or the soil raked: the grid's
// changes into the field, and whether the chassis can reach the soil before the next time. The
// field's collision with a geom costs MuJoCo a pass over every cell under the geom's box (the axles span 27 cells by 4) even when nothing touches, as much as
// the soil model's own step; so the field is met only while some geom comes within
// kSoilFieldReachM (2 cm) of the soil under it. A heap that rises or a chassis that sinks faster
// than 2 cm in 10 ms, 2 m/s, would be missed.
void RoverPhysics::Impl::update_soil_field() {
  copy_soil_to_field();
  model->geom_conaffinity[soil_field_geom] = chassis_near_soil() ? 2 : 0;
}

void RoverPhysics::Impl::apply_soft_soil() {
  if (!soft_soil) return;
  follow_with_soil_window();
  const mjModel& m = *model;
  mjData& d = *data;
  std::array<soil::WheelKinematics, kWheelCount> wheels{};
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    const int body = ids.wheel_body[wheel];
    mjtNum velocity[6];  // world-oriented: angular, then linear at the wheel's centre
    mj_objectVelocity(&m, &d, mjOBJ_BODY, body, velocity, 0);
    const mjtNum* rotation = d.xmat + 9 * body;
    soil::WheelKinematics& kinematics = wheels[wheel];
    kinematics.center_m = {d.xpos[3 * body], d.xpos[3 * body + 1], d.xpos[3 * body + 2]};
    kinematics.axle = {rotation[1], rotation[4], rotation[7]};
    kinematics.velocity_mps = {velocity[3], velocity[4], velocity[5]};
    kinematics.spin_radps = soil::dot({velocity[0], velocity[1], velocity[2]}, kinematics.axle);
    if (m.geom_contype[ids.wheel_geom[wheel]] == 0) kinematics.center_m[2] += kLiftedM;
  }
  const std::vector<soil::WheelWrench> wrenches = soft_soil->step(wheels, m.opt.timestep);
  if (soft_soil->yielded()) update_soil_field();  // the grid changes only when it yields
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    const int body = ids.wheel_body[wheel];
    const soil::WheelWrench& wrench = wrenches[wheel];
    const soil::Vec3 lever =
        wheels[wheel].center_m -
        soil::Vec3{d.xipos[3 * body], d.xipos[3 * body + 1], d.xipos[3 * body + 2]};
    const soil::Vec3 torque = wrench.torque_nm + soil::cross(lever, wrench.force_n);
    for (int k = 0; k < 3; ++k) {
      d.xfrc_applied[6 * body + k] = wrench.force_n[static_cast<std::size_t>(k)];
      d.xfrc_applied[6 * body + 3 + k] = torque[static_cast<std::size_t>(k)];
    }
    soil_wrenches[wheel] = wrench;
  }
}

}  // namespace marsokhod::sim
