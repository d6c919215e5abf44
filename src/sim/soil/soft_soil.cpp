#include "sim/soil/soft_soil.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace marsokhod::sim::soil {
namespace {

// Repose relaxation around a wheel: this many cells beyond its box, at most this many passes.
constexpr int kRelaxMarginCells = 3;
constexpr int kRelaxPasses = 4;
// The exit angle's search: steps over [−θ1, 0], and how far above its bowl a rim still touches.
constexpr int kExitSteps = 16;
constexpr double kTouchM = 1e-4;

}  // namespace

SoftSoil::SoftSoil(SoilParams soil, GridSpec grid,
                   const std::function<double(double, double)>& surface_m,
                   const std::vector<WheelGeometry>& wheels)
    : soil_(soil), grid_(grid, soil, surface_m) {
  contacts_.reserve(wheels.size());
  for (const WheelGeometry& wheel : wheels) contacts_.emplace_back(soil_, wheel);
}

Vec3 SoftSoil::ground_normal(const WheelKinematics& kinematics, std::size_t wheel) const {
  return grid_.normal(kinematics.center_m[0], kinematics.center_m[1],
                      2.0 * contacts_.at(wheel).wheel().rim_radius_m);
}

// θ2: stepping back from the bottom, where the rim rises above the soil further than it is above it
// at the bottom (a rim resting in its rebound touches its whole bowl), interpolated between the
// steps so that it moves continuously with the wheel.
double SoftSoil::exit_angle_rad(const Vec3& axis_point, const Vec3& forward, const Vec3& up,
                                double radius_m, double sinkage_m) const {
  const double entry = std::acos(1.0 - std::clamp(sinkage_m, 0.0, radius_m) / radius_m);
  const auto height = [&](double theta) {  // of the rim above the soil
    const Vec3 rim =
        axis_point + (radius_m * std::sin(theta)) * forward - (radius_m * std::cos(theta)) * up;
    return rim[2] - grid_.surface_m(rim[0], rim[1]);
  };
  const double bottom = std::max(height(0.0), 0.0);
  const auto clearance = [&](double theta) { return height(theta) - bottom - kTouchM; };
  double previous_theta = 0.0, previous = clearance(0.0);
  for (int k = 1; k <= kExitSteps; ++k) {
    const double theta = -entry * k / kExitSteps;
    const double current = clearance(theta);
    if (current > 0.0) {
      return previous_theta + (theta - previous_theta) * (-previous) / (current - previous);
    }
    previous_theta = theta;
    previous = current;
  }
  return -entry;
}

SoftSoil::LaneContacts SoftSoil::lane_contacts(std::size_t wheel,
                                               const WheelKinematics& kinematics) const {
  const WheelSoilContact& contact = contacts_.at(wheel);
  const auto lanes = static_cast<std::size_t>(contact.wheel().lanes);
  LaneContacts result{std::vector<double>(lanes, 0.0), std::vector<double>(lanes, 0.0)};
  const Vec3 normal = ground_normal(kinematics, wheel);
  const Vec3 rolling = cross(kinematics.axle, normal);
  if (norm(rolling) < 1e-9) return result;
  const Vec3 forward = (static_cast<double>(contact.direction()) / norm(rolling)) * rolling;
  const Vec3 up = (1.0 / norm(rolling)) * cross(rolling, kinematics.axle);
  const double radius = contact.wheel().rim_radius_m;
  for (std::size_t lane = 0; lane < lanes; ++lane) {
    const Vec3 axis_point =
        kinematics.center_m + contact.lane_offset_m(static_cast<int>(lane)) * kinematics.axle;
    const Vec3 lowest = axis_point - radius * up;
    const double surface = grid_.surface_m(lowest[0], lowest[1]);
    const double undisturbed = grid_.undisturbed_m(lowest[0], lowest[1]);
    const double gap = std::max(lowest[2] - surface, 0.0);
    const double depth =
        undisturbed - std::min(lowest[2], surface) - soil_.unloading_stiffness_ratio * gap;
    result.sinkage_m[lane] = depth * normal[2];
    if (result.sinkage_m[lane] > 0.0) {
      result.exit_rad[lane] =
          exit_angle_rad(axis_point, forward, up, radius, result.sinkage_m[lane]);
    }
  }
  return result;
}

std::vector<WheelWrench> SoftSoil::step(std::span<const WheelKinematics> wheels, double dt_s) {
  if (wheels.size() != contacts_.size() || !(dt_s > 0.0) || !std::isfinite(dt_s)) {
    std::ostringstream message;
    message << "SoftSoil::step: expected " << contacts_.size()
            << " wheels and a finite dt_s > 0, got " << wheels.size() << " and " << dt_s;
    throw std::invalid_argument(message.str());
  }
  std::vector<WheelWrench> wrenches;
  wrenches.reserve(wheels.size());
  for (std::size_t i = 0; i < wheels.size(); ++i) {
    const LaneContacts lanes = lane_contacts(i, wheels[i]);
    wrenches.push_back(contacts_[i].step(wheels[i], ground_normal(wheels[i], i), lanes.sinkage_m,
                                         lanes.exit_rad, dt_s));
  }
  for (std::size_t i = 0; i < wheels.size(); ++i) deform(i, wheels[i], wrenches[i], dt_s);
  return wrenches;
}

void SoftSoil::deform(std::size_t wheel, const WheelKinematics& kinematics,
                      const WheelWrench& wrench, double dt_s) {
  const WheelGeometry& geometry = contacts_[wheel].wheel();
  const Cylinder cylinder{kinematics.center_m, kinematics.axle, geometry.rim_radius_m,
                          geometry.width_m};
  const Footprint footprint = grid_.press(cylinder);
  if (wrench.diagnostics.in_contact && geometry.bladed) {
    const Vec3 normal = ground_normal(kinematics, wheel);
    const Vec3 rolling = cross(kinematics.axle, normal);
    const Vec3 forward = (1.0 / std::max(norm(rolling), 1e-12)) * rolling;
    const double direction = contacts_[wheel].direction();
    const double slip_speed = direction * (geometry.shear_radius_m() * kinematics.spin_radps -
                                           dot(kinematics.velocity_mps, forward));
    const std::vector<double> sinkage = lane_contacts(wheel, kinematics).sinkage_m;
    const double in_contact = static_cast<double>(std::count_if(sinkage.begin(), sinkage.end(),
                                                                [](double z) { return z > 0.0; })) /
                              geometry.lanes;
    const double volume = soil_.excavation_fraction * geometry.width_m * geometry.blade_height_m *
                          std::max(slip_speed, 0.0) * dt_s * in_contact;
    grid_.excavate(footprint, cylinder, direction * forward,
                   geometry.rim_radius_m + grid_.spec().cell_m, volume);
  }
  grid_.relax(footprint, kRelaxMarginCells, kRelaxPasses);
}

}  // namespace marsokhod::sim::soil
