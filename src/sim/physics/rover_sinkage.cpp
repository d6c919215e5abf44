// Skid sinkage (terrain.hpp): a wheel dragged over loose ground faster than it turns ploughs.
// Each step, before MuJoCo's, every wheel touching a sinking material gets the sliding friction
// μ + skid_sinkage·s for that step (MuJoCo mixes a contact's friction as the larger of its two
// geoms'), s from the contacts and velocities of the last step.
#include <algorithm>
#include <cmath>
#include <string>

#include "sim/physics/rover_physics_impl.hpp"

namespace marsokhod::sim {
namespace {

// Below this hub speed the skid ratio fades to 0, so that the friction is continuous at rest.
constexpr double kSkidSpeedFloorMps = 0.01;

using Vec3 = std::array<double, 3>;

Vec3 cross(const Vec3& u, const Vec3& v) {
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}
double dot(const Vec3& u, const Vec3& v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }

// s ∈ [0, 1]: along the wheel's heading h = axle × n, the speed at which the contact point
// (v + Ω × (−r·n)) slides the same way as the hub moves, over the hub's speed (floored).
double skid_ratio(const mjModel& model, const mjData& data, int body, const Vec3& normal,
                  double radius_m) {
  mjtNum velocity[6];  // world-oriented: angular, then linear at the wheel's center
  mj_objectVelocity(&model, &data, mjOBJ_BODY, body, velocity, 0);
  const mjtNum* rotation = data.xmat + 9 * body;
  Vec3 heading = cross({rotation[1], rotation[4], rotation[7]}, normal);
  const double length = std::sqrt(dot(heading, heading));
  if (length < 1e-9) return 0.0;  // the axle stands on its end
  for (double& component : heading) component /= length;
  const Vec3 omega{velocity[0], velocity[1], velocity[2]};
  const Vec3 hub{velocity[3], velocity[4], velocity[5]};
  const Vec3 rim =
      cross(omega, {-radius_m * normal[0], -radius_m * normal[1], -radius_m * normal[2]});
  const double hub_mps = dot(hub, heading);
  if (std::abs(hub_mps) < 1e-9) return 0.0;
  const double contact_mps = hub_mps + dot(rim, heading);
  return std::clamp(contact_mps * (hub_mps > 0.0 ? 1.0 : -1.0) /
                        std::max(std::abs(hub_mps), kSkidSpeedFloorMps),
                    0.0, 1.0);
}

}  // namespace

// The terrain geoms by name (terrain_mjcf.cpp): the ground plane or heightfield carry the
// ground's material, obstacle_i the i-th obstacle's.
void RoverPhysics::Impl::resolve_terrain_materials(const TerrainSpec& terrain) {
  const mjModel& m = *model;
  geom_ground_friction.assign(static_cast<std::size_t>(m.ngeom), 0.0);
  geom_skid_sinkage.assign(static_cast<std::size_t>(m.ngeom), 0.0);
  const auto set = [&](int geom, const Material& material) {
    if (geom < 0) return;
    geom_ground_friction[static_cast<std::size_t>(geom)] = material.sliding_friction;
    geom_skid_sinkage[static_cast<std::size_t>(geom)] = material.skid_sinkage;
  };
  set(mj_name2id(&m, mjOBJ_GEOM, "ground"), terrain.ground);
  set(mj_name2id(&m, mjOBJ_GEOM, "heightfield"), terrain.ground);
  for (std::size_t i = 0; i < terrain.obstacles.size(); ++i) {
    set(mj_name2id(&m, mjOBJ_GEOM, ("obstacle_" + std::to_string(i)).c_str()),
        terrain.obstacles[i].material);
  }
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    wheel_own_friction[wheel] = m.geom_friction[3 * ids.wheel_geom[wheel]];
  }
}

void RoverPhysics::Impl::apply_skid_sinkage() {
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    const int geom = ids.wheel_geom[wheel];
    double sinkage = 0.0, ground_friction = 0.0;
    Vec3 normal{0.0, 0.0, 1.0};  // from the ground toward the wheel
    for (int i = 0; i < data->ncon; ++i) {
      const mjContact& contact = data->contact[i];
      if (contact.geom1 != geom && contact.geom2 != geom) continue;
      const auto other = static_cast<std::size_t>(contact.geom1 == geom ? contact.geom2
                                                                        : contact.geom1);
      if (geom_skid_sinkage[other] <= sinkage) continue;
      sinkage = geom_skid_sinkage[other];
      ground_friction = geom_ground_friction[other];
      const double sign = contact.geom2 == geom ? 1.0 : -1.0;  // MuJoCo's normal: geom1 → geom2
      normal = {sign * contact.frame[0], sign * contact.frame[1], sign * contact.frame[2]};
    }
    const double skid =
        sinkage > 0.0 ? skid_ratio(*model, *data, ids.wheel_body[wheel], normal,
                                   params.geometry.wheel_radius_m)
                      : 0.0;
    model->geom_friction[3 * geom] =
        skid > 0.0 ? ground_friction + sinkage * skid : wheel_own_friction[wheel];
  }
}

}  // namespace marsokhod::sim
