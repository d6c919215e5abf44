#include "sim/physics/rover_urdf.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "sim/physics/chassis_geometry.hpp"
#include "sim/physics/mujoco_model.hpp"
#include "sim/physics/rover_kinematics.hpp"
#include "sim/physics/rover_mjcf.hpp"
#include "sim/physics/xml_writer.hpp"

namespace marsokhod::sim {
namespace {

std::string vec3(double x, double y, double z) { return xml_numbers(Vec3{x, y, z}); }

// A body's mass, centre of mass and inertia tensor in the body's frame, from MuJoCo's principal
// inertia (body_inertia about the axes of body_iquat at body_ipos).
void write_inertial(XmlWriter& xml, const mjModel& model, const std::string& body) {
  const int id = require_id(model, mjOBJ_BODY, body);
  std::array<mjtNum, 9> r{};
  mju_quat2Mat(r.data(), model.body_iquat + 4 * id);
  const mjtNum* d = model.body_inertia + 3 * id;
  // I = R · diag(d) · Rᵀ
  std::array<double, 9> inertia{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      double sum = 0.0;
      for (int k = 0; k < 3; ++k) sum += r[3 * i + k] * d[k] * r[3 * j + k];
      // Exact zeros where rounding leaves 1e-19.
      inertia[3 * i + j] = std::abs(sum) < 1e-12 ? 0.0 : sum;
    }
  }
  const mjtNum* c = model.body_ipos + 3 * id;
  xml.open("inertial");
  xml.leaf("origin", {{"xyz", vec3(c[0], c[1], c[2])}, {"rpy", "0 0 0"}});
  xml.leaf("mass", {{"value", xml_number(model.body_mass[id])}});
  xml.leaf("inertia", {{"ixx", xml_number(inertia[0])},
                       {"ixy", xml_number(inertia[1])},
                       {"ixz", xml_number(inertia[2])},
                       {"iyy", xml_number(inertia[4])},
                       {"iyz", xml_number(inertia[5])},
                       {"izz", xml_number(inertia[8])}});
  xml.close();
}

// A shape as both visual and collision.
void write_shape(XmlWriter& xml, const std::string& origin_xyz, const std::string& origin_rpy,
                 const std::string& tag, const XmlWriter::Attributes& size) {
  for (const char* element : {"visual", "collision"}) {
    xml.open(element);
    xml.leaf("origin", {{"xyz", origin_xyz}, {"rpy", origin_rpy}});
    xml.open("geometry");
    xml.leaf(tag, size);
    xml.close();
    xml.close();
  }
}

// A rod from the frame's origin to (x, 0, z): URDF's cylinder runs along z, turned about y.
void write_rod(XmlWriter& xml, double x, double z, double radius_m) {
  write_shape(xml, vec3(x / 2, 0.0, z / 2), vec3(0.0, std::atan2(x, z), 0.0), "cylinder",
              {{"radius", xml_number(radius_m)}, {"length", xml_number(std::hypot(x, z))}});
}

// Opens the joint element (the caller adds its limits and closes it).
void write_joint(XmlWriter& xml, const RoverJoint& joint) {
  xml.open("joint", {{"name", joint.name}, {"type", joint.type}});
  xml.leaf("parent", {{"link", joint.parent}});
  xml.leaf("child", {{"link", joint.child}});
  xml.leaf("origin", {{"xyz", xml_numbers(joint.xyz)}, {"rpy", xml_numbers(joint.rpy)}});
  xml.leaf("axis", {{"xyz", xml_numbers(joint.axis)}});
}

void write_limit(XmlWriter& xml, double lower, double upper, double effort, double velocity) {
  xml.leaf("limit", {{"lower", xml_number(lower)},
                     {"upper", xml_number(upper)},
                     {"effort", xml_number(effort)},
                     {"velocity", xml_number(velocity)}});
}

struct Urdf {
  const Params& params;
  const mjModel& model;
  std::vector<RoverJoint> joints;
  XmlWriter xml;
  const RoverJoint& joint(const std::string& name) const {
    for (const RoverJoint& j : joints) {
      if (j.name == name) return j;
    }
    throw std::logic_error("urdf: no joint " + name);
  }
  double stall_nm() const {
    return params.motors.max_no_load_speed_radps / params.load.gain_same_sign_radps_per_nm;
  }

  void wheel(std::size_t wheel) {
    const std::string name = wheel_name(wheel);
    xml.open("link", {{"name", name}});
    write_inertial(xml, model, name);
    write_shape(xml, "0 0 0", vec3(std::numbers::pi / 2, 0.0, 0.0), "cylinder",
                {{"radius", xml_number(params.geometry.wheel_radius_m)},
                 {"length", xml_number(kWheelWidthM)}});
    xml.close();
    write_joint(xml, joint(name));
    xml.leaf("limit", {{"effort", xml_number(stall_nm())},
                       {"velocity", xml_number(params.motors.max_no_load_speed_radps)}});
    xml.close();
  }

  void lever(bool front) {
    const GeometryParams& g = params.geometry;
    const std::string prefix = front ? "front" : "rear";
    const double a = g.joint_to_exterior_axle_m;
    const std::size_t motor = front ? kFrontJoint : kRearJoint;
    const RoverJoint& hinge = joint(joint_hinge_name(motor));
    const double reach = hinge.xyz[0];

    xml.open("link", {{"name", prefix + "_strut"}});
    write_inertial(xml, model, prefix + "_strut");
    write_rod(xml, reach, a, 0.03);
    xml.close();
    write_joint(xml, joint("strut_" + prefix));
    write_limit(xml, -kStrutPivotRangeRad, kStrutPivotRangeRad, 0.0, 0.0);
    if (!front) xml.leaf("mimic", {{"joint", "strut_front"}, {"multiplier", "-1"}, {"offset", "0"}});
    xml.leaf("dynamics", {{"damping", xml_number(kPassiveDampingNmsPerRad)}});
    xml.close();

    xml.open("link", {{"name", prefix + "_lever"}});
    write_inertial(xml, model, prefix + "_lever");
    write_rod(xml, 0.0, -a, 0.03);
    xml.close();
    const JointParams& j = params.joints;
    write_joint(xml, hinge);
    write_limit(xml, front ? j.front_min_rad : j.rear_min_rad,
                front ? j.front_max_rad : j.rear_max_rad, stall_nm(),
                params.motors.max_no_load_speed_radps);
    xml.close();

    const double half_track = g.track_width_m / 2;
    const double beam = half_track - kWheelWidthM / 2 - 0.005;
    xml.open("link", {{"name", prefix + "_axle"}});
    write_inertial(xml, model, prefix + "_axle");
    write_shape(xml, "0 0 0", vec3(std::numbers::pi / 2, 0.0, 0.0), "cylinder",
                {{"radius", "0.04"}, {"length", xml_number(2 * beam)}});
    xml.close();
    write_joint(xml, joint(front ? kFrontTiltName : kRearTiltName));
    write_limit(xml, -kMaxAxleTiltRad, kMaxAxleTiltRad, 0.0, 0.0);
    xml.leaf("dynamics", {{"damping", xml_number(kPassiveDampingNmsPerRad)}});
    xml.close();
    wheel(front ? kFrontLeft : kBackLeft);
    wheel(front ? kFrontRight : kBackRight);
  }

  void center_unit() {
    const GeometryParams& g = params.geometry;
    xml.open("link", {{"name", "base_link"}});
    write_inertial(xml, model, kCenterUnitName);
    const double half_width = g.track_width_m / 2 - kWheelWidthM / 2 - 0.05;
    write_shape(xml, vec3(0.0, 0.0, 0.17), "0 0 0", "box", {{"size", vec3(0.5, 2 * half_width, 0.14)}});
    xml.close();
    wheel(kCenterLeft);
    wheel(kCenterRight);
    lever(true);
    lever(false);
  }
};

}  // namespace

std::string rover_urdf(const Params& params) {
  validate_geometry(params.geometry);
  const ModelPtr model = load_rover_model(params, TerrainSpec{}, 0.002);
  Urdf urdf{params, *model, rover_joints(params), {}};
  urdf.xml.open("robot", {{"name", "marsokhod"}});
  urdf.center_unit();
  urdf.xml.close();
  return "<?xml version=\"1.0\"?>\n<!-- Generated by `marsokhod urdf` from the configuration's "
         "geometry (src/sim/physics/rover_urdf.hpp). -->\n" +
         urdf.xml.text();
}

}  // namespace marsokhod::sim
