#include "sim/physics/rover_mjcf.hpp"

#include <cmath>
#include <stdexcept>

#include "sim/physics/chassis_geometry.hpp"
#include "sim/physics/terrain_mjcf.hpp"
#include "sim/physics/xml_writer.hpp"

namespace marsokhod::sim {
namespace {

using Attributes = XmlWriter::Attributes;

// Contact buffers: a wheel on a plane makes a few contacts, on a heightfield up to MuJoCo's 50
// per geom pair; each contact takes at most 6 constraint rows (condim 6, elliptic cone). On soft
// soil the wheels meet only obstacles, and the chassis the soil's height field (condim 3: 3 rows)
// at up to 50 contacts a geom: two exterior axles resting on the soil between the ruts make
// 100–120, so 250, at 4 rows on average. (MuJoCo 2.2 allocates njmax² numbers for the
// constraints' matrix: 9 MB here, 48 MB for a heightfield's 400, 5 MB for 120.)
struct ContactCapacity {
  int contacts = 120;
  int rows = 120 * 6 + 64;
};
ContactCapacity contact_capacity(const TerrainSpec& terrain) {
  if (terrain.kind == TerrainKind::kHeightfield) return {400, 400 * 6 + 64};
  if (terrain.ground.soil) return {250, 250 * 4 + 64};
  return {};
}

std::string vec3(double x, double y, double z) {
  return xml_numbers(std::array<double, 3>{x, y, z});
}

void write_header(XmlWriter& xml, const Params& params, const TerrainSpec& terrain,
                  double timestep_s) {
  xml.leaf("compiler", {{"angle", "radian"}});
  // The motors' speed–torque lines are velocity feedback integrated implicitly: it must be for the
  // joint lock's brake (10⁴ N·m·s/rad), and for the lines themselves (1/droop ≈ 33) it keeps the
  // numbers of the implicit integrator. MuJoCo's Euler integrator is implicit in dof damping, and
  // RoverPhysics moves each line's velocity gain into its shaft's damping every step
  // (rover_physics.cpp, apply_motor_lines): the "implicit" integrator's step without the velocity
  // derivative of the Coriolis forces, which cost half the step (BENCHMARKS.md). MuJoCo's
  // friction is soft: a held rover creeps down a slope; the elliptic cone with impratio 10 cuts
  // the creep on 15° to 0.1 mm/s (1 mm/s with the defaults).
  xml.leaf("option", {{"timestep", xml_number(timestep_s)},
                      {"integrator", "Euler"},
                      {"cone", "elliptic"},
                      {"impratio", "10"},
                      {"gravity", vec3(0.0, 0.0, -params.sensors.gravity_mps2)}});
  const ContactCapacity capacity = contact_capacity(terrain);
  xml.leaf("size", {{"nconmax", std::to_string(capacity.contacts)},
                    {"njmax", std::to_string(capacity.rows)}});
  xml.open("default");
  // The rover's own geoms: near-zero friction so that the terrain's material decides (MuJoCo
  // takes the larger coefficient of a pair). Contact bits: terrain geoms have conaffinity 1, a
  // soft-soil ground plane 2; the chassis (contype 3) meets both, a wheel (contype 1) only the
  // rigid ones — on soft soil the soil model carries it.
  xml.open("default", {{"class", kRoverGeomClass}});
  xml.leaf("geom", {{"contype", "3"},
                    {"conaffinity", "0"},
                    {"group", std::to_string(kRoverGeomGroup)},
                    {"friction", "0.001 0 0"},
                    {"condim", "3"}});
  xml.close();
  xml.open("default", {{"class", "terrain"}});
  xml.leaf("geom", {{"contype", "0"}, {"conaffinity", "1"}, {"group", "0"}});
  xml.close();
  xml.close();
}

void write_wheel(XmlWriter& xml, std::size_t wheel, double lateral_m, double radius_m) {
  const std::string name = wheel_name(wheel);
  xml.open("body", {{"name", name}, {"pos", vec3(0.0, lateral_m, 0.0)}});
  xml.leaf("joint", {{"name", name},
                     {"type", "hinge"},
                     {"axis", "0 1 0"},
                     {"armature", xml_number(kMotorReflectedInertiaKgM2)}});
  xml.leaf("geom", {{"name", name},
                    {"class", kRoverGeomClass},
                    {"type", "cylinder"},
                    {"contype", "1"},
                    {"size", xml_numbers(std::array<double, 2>{radius_m, kWheelWidthM / 2})},
                    {"zaxis", "0 1 0"},
                    {"mass", xml_number(kWheelMassKg)}});
  xml.close();
}

struct LeverSide {
  const char* prefix;       // "front", "rear"
  std::size_t joint_motor;  // 6, 7
  std::size_t left_wheel, right_wheel;
  double direction;  // +1 front, −1 rear: which way along x the lever reaches
};

// The side view laid out with the joint vertical (γ = arccos(a/b)): the joint at (reach, a) from
// the center axle, the exterior axle straight below it, level with the center axle.
// p6 = −γf and p7 = +γr are the hinges' own values: `ref` is the layout's angle, and increasing γ
// swings the lever away from the center axle, so the front hinge's angle runs negative.
struct LeverLayout {
  double reach_m, height_m;  // the joint's position
  double ref_rad;            // the hinge value of the layout
  double low_rad, high_rad;  // the mechanical stops as hinge values
};

LeverLayout lever_layout(const GeometryParams& geometry, const LeverSide& side) {
  const double a = geometry.joint_to_exterior_axle_m;
  const double b = geometry.center_axle_to_joint_m;
  const BendRange bend = mechanical_bend_range(geometry);
  const bool front = side.direction > 0;
  return {side.direction * std::sqrt(b * b - a * a), a,
          (front ? -1.0 : 1.0) * vertical_bend_rad(geometry), front ? -bend.max_rad : bend.min_rad,
          front ? -bend.min_rad : bend.max_rad};
}

std::string range(double low, double high) { return xml_number(low) + " " + xml_number(high); }
std::string constraint_solref() { return xml_number(kConstraintTimeConstantS) + " 1"; }

// The joint motor's output shaft: a body of its own about the joint's axis, reaching the lever only
// through the gap and the lock.
void write_shaft(XmlWriter& xml, const LeverLayout& layout, const LeverSide& side,
                 double backlash_rad) {
  xml.open("body", {{"name", std::string(side.prefix) + "_shaft"},
                    {"pos", vec3(layout.reach_m, 0.0, layout.height_m)}});
  xml.leaf("joint", {{"name", shaft_hinge_name(side.joint_motor)},
                     {"type", "hinge"},
                     {"axis", "0 1 0"},
                     {"ref", xml_number(layout.ref_rad)},
                     {"limited", "true"},
                     {"range", range(layout.low_rad, layout.high_rad + backlash_rad)},
                     {"armature", xml_number(kMotorReflectedInertiaKgM2)},
                     {"solreflimit", constraint_solref()}});
  xml.leaf(
      "inertial",
      {{"pos", "0 0 0"}, {"mass", xml_number(kShaftMassKg)}, {"diaginertia", "1e-5 1e-5 1e-5"}});
  xml.close();
}

// The roll-hinged exterior axle with its two wheels, at the lever's lower end.
void write_exterior_axle(XmlWriter& xml, const GeometryParams& geometry, const LeverSide& side) {
  xml.open("body", {{"name", std::string(side.prefix) + "_axle"},
                    {"pos", vec3(0.0, 0.0, -geometry.joint_to_exterior_axle_m)}});
  xml.leaf("joint", {{"name", side.direction > 0 ? kFrontTiltName : kRearTiltName},
                     {"type", "hinge"},
                     {"axis", "1 0 0"},
                     {"limited", "true"},
                     {"range", range(-kMaxAxleTiltRad, kMaxAxleTiltRad)},
                     {"damping", xml_number(kPassiveDampingNmsPerRad)}});
  const double half_track_m = geometry.track_width_m / 2;
  const double beam_m = half_track_m - kWheelWidthM / 2 - kAxleEndGapM;
  xml.leaf("geom", {{"class", kRoverGeomClass},
                    {"type", "capsule"},
                    {"size", xml_number(kAxleRadiusM)},
                    {"fromto", vec3(0.0, -beam_m, 0.0) + " " + vec3(0.0, beam_m, 0.0)},
                    {"mass", xml_number(kAxleMassKg)}});
  write_wheel(xml, side.left_wheel, half_track_m, geometry.wheel_radius_m);
  write_wheel(xml, side.right_wheel, -half_track_m, geometry.wheel_radius_m);
  xml.close();
}

// One end of the chassis: the strut pivoting about the center axle, the joint motor's shaft, the
// lever on the joint and the exterior axle.
void write_lever(XmlWriter& xml, const Params& params, const LeverSide& side) {
  const LeverLayout layout = lever_layout(params.geometry, side);
  const std::string prefix = side.prefix;
  const std::string joint_pos = vec3(layout.reach_m, 0.0, layout.height_m);
  xml.open("body", {{"name", prefix + "_strut"}});
  xml.leaf("joint", {{"name", "strut_" + prefix},
                     {"type", "hinge"},
                     {"axis", "0 1 0"},
                     {"limited", "true"},
                     {"range", range(-kStrutPivotRangeRad, kStrutPivotRangeRad)},
                     {"damping", xml_number(kPassiveDampingNmsPerRad)}});
  xml.leaf("geom", {{"class", kRoverGeomClass},
                    {"type", "capsule"},
                    {"size", "0.03"},
                    {"fromto", "0 0 0 " + joint_pos},
                    {"mass", xml_number(kStrutMassKg)}});
  write_shaft(xml, layout, side, params.motors.backlash_rad[side.joint_motor]);
  xml.open("body", {{"name", prefix + "_lever"}, {"pos", joint_pos}});
  xml.leaf("joint", {{"name", joint_hinge_name(side.joint_motor)},
                     {"type", "hinge"},
                     {"axis", "0 1 0"},
                     {"ref", xml_number(layout.ref_rad)},
                     {"limited", "true"},
                     {"range", range(layout.low_rad, layout.high_rad)},
                     {"solreflimit", constraint_solref()}});
  xml.leaf("geom",
           {{"class", kRoverGeomClass},
            {"type", "capsule"},
            {"size", "0.03"},
            {"fromto", "0 0 0 " + vec3(0.0, 0.0, -params.geometry.joint_to_exterior_axle_m)},
            {"mass", xml_number(kLeverMassKg)}});
  write_exterior_axle(xml, params.geometry, side);
  xml.close();
  xml.close();
}

void write_center_unit(XmlWriter& xml, const Params& params) {
  xml.open("body", {{"name", kCenterUnitName}});
  xml.leaf("freejoint", {{"name", kCenterUnitName}});
  // The electronics box above the center axle, clear of the wheels.
  const double half_width_m = params.geometry.track_width_m / 2 - kWheelWidthM / 2 - 0.05;
  xml.leaf("geom", {{"name", kCenterUnitName},
                    {"class", kRoverGeomClass},
                    {"type", "box"},
                    {"pos", vec3(0.0, 0.0, 0.17)},
                    {"size", vec3(0.25, half_width_m, 0.07)},
                    {"mass", xml_number(kCenterUnitMassKg)}});
  xml.leaf("site", {{"name", kImuSiteName}, {"pos", "0 0 0"}});
  write_wheel(xml, kCenterLeft, params.geometry.track_width_m / 2, params.geometry.wheel_radius_m);
  write_wheel(xml, kCenterRight, -params.geometry.track_width_m / 2,
              params.geometry.wheel_radius_m);
  write_lever(xml, params, {"front", kFrontJoint, kFrontLeft, kFrontRight, 1.0});
  write_lever(xml, params, {"rear", kRearJoint, kBackLeft, kBackRight, -1.0});
  xml.close();
}

// Every motor a velocity servo on its shaft (see rover_mjcf.hpp); unpowered (kv = 0) until the
// first drive.
void write_actuators(XmlWriter& xml) {
  xml.open("actuator");
  for (std::size_t motor = 0; motor < kMotorCount; ++motor) {
    const std::string shaft = motor < kWheelCount ? wheel_name(motor) : shaft_hinge_name(motor);
    xml.leaf("general", {{"name", motor_actuator_name(motor)},
                         {"joint", shaft},
                         {"gainprm", "0"},
                         {"biastype", "affine"},
                         {"biasprm", "0 0 0"},
                         {"forcelimited", "true"},
                         {"forcerange", "-1 1"}});
  }
  xml.close();
}

void write_constraints_and_sensors(XmlWriter& xml) {
  xml.open("equality");
  // The center unit at the struts' mean angle: the pivot angles relative to it are opposite.
  xml.leaf("joint", {{"name", "strut_differential"},
                     {"joint1", "strut_front"},
                     {"joint2", "strut_rear"},
                     {"polycoef", "0 -1 0 0 0"},
                     {"solref", constraint_solref()}});
  const std::string solref = constraint_solref();
  for (std::size_t motor : {kFrontJoint, kRearJoint}) {
    // Both switched by RoverPhysics: the lock holds the joint at an angle, the coupling makes
    // p = p̄ + offset.
    xml.leaf("joint", {{"name", joint_lock_name(motor)},
                       {"joint1", joint_hinge_name(motor)},
                       {"polycoef", "0 0 0 0 0"},
                       {"active", "false"},
                       {"solref", solref}});
    xml.leaf("joint", {{"name", joint_coupling_name(motor)},
                       {"joint1", joint_hinge_name(motor)},
                       {"joint2", shaft_hinge_name(motor)},
                       {"polycoef", "0 1 0 0 0"},
                       {"active", "false"},
                       {"solref", solref}});
  }
  // The stand holds the center unit's frame at the stand's (switched by RoverPhysics).
  xml.leaf("weld", {{"name", kTestStandName},
                    {"body1", kCenterUnitName},
                    {"body2", kTestStandName},
                    {"relpose", "0 0 0 1 0 0 0"},
                    {"active", "false"},
                    {"solref", solref}});
  // A blocked wheel (Field Experiment 6.2): its hinge held at the angle it had, when activated.
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    xml.leaf("joint", {{"name", wheel_block_name(wheel)},
                       {"joint1", wheel_name(wheel)},
                       {"polycoef", "0 0 0 0 0"},
                       {"active", "false"},
                       {"solref", solref}});
  }
  xml.close();
  xml.open("sensor");
  xml.leaf("accelerometer", {{"name", kAccelerometerName}, {"site", kImuSiteName}});
  xml.close();
}

}  // namespace

std::string wheel_name(std::size_t wheel) { return std::string("wheel_") + kMotorNames.at(wheel); }
std::string motor_actuator_name(std::size_t motor) {
  return std::string("motor_") + kMotorNames.at(motor);
}
std::string joint_hinge_name(std::size_t motor) {
  return std::string("joint_") + kMotorNames.at(motor);
}
std::string shaft_hinge_name(std::size_t motor) {
  return std::string("shaft_") + kMotorNames.at(motor);
}
std::string joint_lock_name(std::size_t motor) {
  return std::string("lock_") + kMotorNames.at(motor);
}
std::string joint_coupling_name(std::size_t motor) {
  return std::string("couple_") + kMotorNames.at(motor);
}
std::string wheel_block_name(std::size_t wheel) {
  return std::string("block_") + kMotorNames.at(wheel);
}

std::string rover_mjcf(const Params& params, const TerrainSpec& terrain, double timestep_s) {
  validate_geometry(params.geometry);
  validate(terrain);
  if (!(timestep_s > 0.0 && timestep_s <= 0.01)) {
    throw std::invalid_argument("physics: the timestep must lie in (0, 0.01] s, got " +
                                xml_number(timestep_s));
  }
  XmlWriter xml;
  xml.open("mujoco", {{"model", "marsokhod"}});
  write_header(xml, params, terrain, timestep_s);
  xml.open("asset");
  write_terrain_assets(xml, terrain);
  xml.close();
  xml.open("worldbody");
  write_terrain_geoms(xml, terrain);
  write_center_unit(xml, params);
  // The calibration stand (Procedures 3.3, 4.4–4.13): a mocap frame the center unit is welded to
  // while the rover is on the stand; no geometry, so it touches nothing.
  xml.leaf("body", {{"name", kTestStandName}, {"mocap", "true"}, {"pos", "0 0 -10"}});
  xml.close();
  write_actuators(xml);
  write_constraints_and_sensors(xml);
  xml.close();
  return xml.text();
}

}  // namespace marsokhod::sim
