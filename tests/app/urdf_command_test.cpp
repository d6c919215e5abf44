// `marsokhod urdf`: the numbers of the URDF against the configuration and the MuJoCo model, and
// Debian's urdfdom parser (check_urdf, package liburdfdom-tools) on the real binary's output.
#include "cli_runner.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>

#include "config/load_params.hpp"
#include "core/checks/checks.hpp"
#include "sim/physics/chassis_geometry.hpp"
#include "sim/physics/mujoco_model.hpp"
#include "sim/physics/rover_mjcf.hpp"

namespace marsokhod::app {
namespace {

using test::cli;
using test::Result;

const std::string kConfig = std::string(MARSOKHOD_SOURCE_DIR) + "/config/marsokhod.toml";

std::string urdf_text() {
  const Result r = cli({"--config", kConfig.c_str(), "urdf"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  return r.out;
}

// The element <tag name="NAME" …> … </tag> (joints and links), as text.
std::string element(const std::string& xml, const std::string& tag, const std::string& name) {
  const std::string open = "<" + tag + " name=\"" + name + "\"";
  const auto begin = xml.find(open);
  if (begin == std::string::npos) return "";
  const auto end = xml.find("</" + tag + ">", begin);
  return xml.substr(begin, end - begin);
}

// The attributes of the first <child …/> element inside `text`.
std::map<std::string, double> numbers_of(const std::string& text, const std::string& child) {
  std::map<std::string, double> out;
  const auto begin = text.find("<" + child + " ");
  if (begin == std::string::npos) return out;
  const std::string tag = text.substr(begin, text.find('>', begin) - begin);
  static const std::regex attribute("([a-z]+)=\"([-+0-9.e]+)\"");
  for (auto it = std::sregex_iterator(tag.begin(), tag.end(), attribute); it != std::sregex_iterator();
       ++it) {
    out[(*it)[1]] = std::stod((*it)[2]);
  }
  return out;
}

std::string attribute_text(const std::string& text, const std::string& child,
                           const std::string& name) {
  const std::regex pattern("<" + child + " [^>]*" + name + "=\"([^\"]*)\"");
  std::smatch m;
  return std::regex_search(text, m, pattern) ? m[1].str() : "";
}

TEST(UrdfCommand, JointLimitsAreTheParamsBounds) {
  const Params params = config::load_params(kConfig);
  const std::string xml = urdf_text();
  const auto front = numbers_of(element(xml, "joint", "joint_AF"), "limit");
  const auto rear = numbers_of(element(xml, "joint", "joint_AR"), "limit");
  ASSERT_EQ(front.count("lower"), 1u) << xml;
  EXPECT_EQ(front.at("lower"), params.joints.front_min_rad);
  EXPECT_EQ(front.at("upper"), params.joints.front_max_rad);
  EXPECT_EQ(rear.at("lower"), params.joints.rear_min_rad);
  EXPECT_EQ(rear.at("upper"), params.joints.rear_max_rad);
  EXPECT_EQ(front.at("velocity"), params.motors.max_no_load_speed_radps);
  // The passive axle roll within the chapter 3.1 table's ±0.524 rad.
  const auto tilt = numbers_of(element(xml, "joint", "tilt_front"), "limit");
  EXPECT_EQ(tilt.at("lower"), -sim::kMaxAxleTiltRad);
  EXPECT_EQ(tilt.at("upper"), sim::kMaxAxleTiltRad);
  EXPECT_EQ(attribute_text(element(xml, "joint", "tilt_rear"), "axis", "xyz"), "1 0 0");
  EXPECT_EQ(attribute_text(element(xml, "joint", "strut_rear"), "mimic", "joint"), "strut_front");
}

TEST(UrdfCommand, WheelsHaveTheConfigurationsRadiusAndTrack) {
  const Params params = config::load_params(kConfig);
  const std::string xml = urdf_text();
  for (const char* wheel : {"FL", "FR", "CL", "CR", "BL", "BR"}) {
    const std::string name = std::string("wheel_") + wheel;
    const std::string link = element(xml, "link", name);
    ASSERT_FALSE(link.empty()) << name;
    EXPECT_EQ(numbers_of(link, "cylinder").at("radius"), params.geometry.wheel_radius_m) << name;
    const std::string joint = element(xml, "joint", name);
    EXPECT_EQ(attribute_text(joint, "joint", "type"), "continuous") << name;
    const std::string xyz = attribute_text(joint, "origin", "xyz");
    const double lateral = std::stod(xyz.substr(xyz.find(' ') + 1));
    EXPECT_EQ(std::abs(lateral), params.geometry.track_width_m / 2) << name;
    EXPECT_EQ(lateral > 0, wheel[1] == 'L') << name;
  }
  // The joint 6 at (sqrt(b² − a²), 0, a) from the center axle; the exterior axle a below it.
  const double a = params.geometry.joint_to_exterior_axle_m;
  const double b = params.geometry.center_axle_to_joint_m;
  const std::string joint = element(xml, "joint", "joint_AF");
  EXPECT_EQ(attribute_text(joint, "origin", "xyz"),
            checks::format_number(std::sqrt(b * b - a * a)) + " 0 " + checks::format_number(a));
  EXPECT_EQ(attribute_text(joint, "origin", "rpy"),
            "0 " + checks::format_number(sim::vertical_bend_rad(params.geometry)) + " 0");
  EXPECT_EQ(attribute_text(element(xml, "joint", "tilt_front"), "origin", "xyz"),
            "0 0 " + checks::format_number(-a));
}

TEST(UrdfCommand, MassesAndInertiasAreTheMujocoModels) {
  const Params params = config::load_params(kConfig);
  const std::string xml = urdf_text();
  const sim::ModelPtr model = sim::load_rover_model(params, sim::TerrainSpec{}, 0.002);
  double urdf_total = 0.0;
  static const std::regex mass("<mass value=\"([-+0-9.e]+)\"");
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), mass); it != std::sregex_iterator();
       ++it) {
    urdf_total += std::stod((*it)[1]);
  }
  // Everything but the two joint shafts' token masses.
  EXPECT_NEAR(urdf_total, mj_getTotalmass(model.get()) - 2 * sim::kShaftMassKg, 1e-9);
  EXPECT_EQ(numbers_of(element(xml, "link", "base_link"), "mass").at("value"),
            sim::kCenterUnitMassKg);
  EXPECT_EQ(numbers_of(element(xml, "link", "wheel_CL"), "mass").at("value"), sim::kWheelMassKg);
  // A solid cylinder about its axis: m·r²/2 (MuJoCo's own inertia of the wheel geom).
  const auto inertia = numbers_of(element(xml, "link", "wheel_CL"), "inertia");
  const double r = params.geometry.wheel_radius_m;
  EXPECT_NEAR(inertia.at("iyy"), sim::kWheelMassKg * r * r / 2, 1e-9);
  EXPECT_NEAR(inertia.at("ixx"),
              sim::kWheelMassKg * (3 * r * r + sim::kWheelWidthM * sim::kWheelWidthM) / 12, 1e-9);
}

TEST(UrdfCommand, ChangedGeometryChangesTheUrdf) {
  std::ifstream in(kConfig);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find("wheel_radius_m = ");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, text.find('\n', at) - at, "wheel_radius_m = 0.115");
  const auto file = std::filesystem::temp_directory_path() /
                    ("marsokhod-urdf-" + std::to_string(::getpid()) + ".toml");
  std::ofstream(file) << text;
  const Result r = cli({"--config", file.c_str(), "urdf"});
  std::filesystem::remove(file);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(numbers_of(element(r.out, "link", "wheel_FL"), "cylinder").at("radius"), 0.115);
}

// Debian's urdfdom parses the real binary's output as a tree rooted at base_link.
TEST(UrdfCommand, CheckUrdfAcceptsIt) {
  if (std::system("command -v check_urdf >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "check_urdf not installed (Debian package liburdfdom-tools)";
  }
  const auto dir = std::filesystem::temp_directory_path() /
                   ("marsokhod-urdf-check-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string urdf = (dir / "marsokhod.urdf").string();
  const std::string out = (dir / "check.txt").string();
  ASSERT_EQ(std::system((std::string(MARSOKHOD_BIN) + " --config " + kConfig + " urdf > " + urdf)
                            .c_str()),
            0);
  const int status = std::system(("check_urdf " + urdf + " > " + out + " 2>&1").c_str());
  std::ifstream in(out);
  const std::string report((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::filesystem::remove_all(dir);
  EXPECT_EQ(status, 0) << report;
  EXPECT_NE(report.find("robot name is: marsokhod"), std::string::npos) << report;
  EXPECT_NE(report.find("root Link: base_link has 4 child(ren)"), std::string::npos) << report;
  EXPECT_NE(report.find("Successfully Parsed XML"), std::string::npos) << report;
}

}  // namespace
}  // namespace marsokhod::app
