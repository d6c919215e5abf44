// Soft soil under the wheels (terrain.hpp: a ground material with `soil`, sim/soil). The wheels
// pass through the ground plane (contact bits, rover_mjcf.cpp); each step, before MuJoCo's, every
// wheel's centre, axle, velocity and spin go to the soil model and its force and torque come back
// as xfrc_applied on the wheel body, the torque moved from the wheel's centre to its centre of
// mass. The kinematics are those MuJoCo computed at the start of the last step, one step (1 ms)
// old, as the skid sinkage's (rover_sinkage.cpp).
//
// The grid: 2 cm cells from x = −3 m to 9 m and y = −3 m to 3 m around the start, level with the
// ground plane (flat, or x·tan(slope) on a slope). Beyond it the edge cells' heights continue.
// Blades: mirror-symmetric across the rover's middle — the left wheels right-handed, the right
// wheels left-handed (docs/simulator.md), inclined at the geometry's blade_inclination_rad (i);
// rim radius = wheel radius − 1 cm of blade.
#include <cmath>

#include "sim/physics/chassis_geometry.hpp"
#include "sim/physics/rover_mjcf.hpp"
#include "sim/physics/rover_physics_impl.hpp"

namespace marsokhod::sim {
namespace {

using soil::operator+;
using soil::operator-;

constexpr double kBladeHeightM = 0.010;  // chapter 3.1: 0.125 m with blades, 0.115 on granules
constexpr soil::GridSpec kSoilGrid{-3.0, -3.0, 0.02, 600, 300};
// A wheel whose contact is switched off (set_wheel_contact) is shown to the soil this high up.
constexpr double kLiftedM = 10.0;

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
  const double slope = terrain.kind == TerrainKind::kSlope ? std::tan(terrain.slope_rad) : 0.0;
  soft_soil.emplace(
      *terrain.ground.soil, kSoilGrid, [slope](double x_m, double) { return x_m * slope; }, wheels);
}

void RoverPhysics::Impl::apply_soft_soil() {
  if (!soft_soil) return;
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
