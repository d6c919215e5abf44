#include "sim/soil/wheel_stress.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace marsokhod::sim::soil {
namespace {

using detail::mobilised;

}  // namespace

double regularised_slip(double rim_speed_mps, double travel_speed_mps) {
  const double scale =
      std::max({std::abs(rim_speed_mps), std::abs(travel_speed_mps), kSlipSpeedFloorMps});
  return std::clamp((rim_speed_mps - travel_speed_mps) / scale, -1.0, 1.0);
}

ContactArc contact_arc(const SoilParams& soil, double rim_radius_m, double sinkage_m, double slip,
                       double exit_rad, double front_rad) {
  const double sinkage = std::clamp(sinkage_m, 0.0, rim_radius_m);
  return contact_arc_at_entry(soil, rim_radius_m, sinkage_m, slip, exit_rad, front_rad,
                              std::acos(1.0 - sinkage / rim_radius_m));
}

ContactArc contact_arc_at_entry(const SoilParams& soil, double rim_radius_m, double sinkage_m,
                                double slip, double exit_rad, double front_rad, double entry_rad) {
  ContactArc arc;
  const double sinkage = std::clamp(sinkage_m, 0.0, rim_radius_m);
  arc.cos_entry = 1.0 - sinkage / rim_radius_m;
  arc.entry_rad = entry_rad;
  arc.exit_rad = std::clamp(exit_rad, -arc.entry_rad, 0.0);
  arc.front_rad = std::clamp(front_rad, 0.0, arc.entry_rad);
  const double ratio =
      std::clamp(soil.max_stress_angle_c1 + soil.max_stress_angle_c2 * slip, 0.0, 1.0);
  arc.max_stress_rad = ratio * (arc.front_rad + arc.exit_rad);
  arc.sinkage_exponent = soil.sinkage_exponent + soil.slip_sinkage_exponent * std::abs(slip);
  return arc;
}

double equivalent_angle_rad(const ContactArc& arc, double theta_rad) {
  if (theta_rad < arc.max_stress_rad && arc.max_stress_rad > arc.exit_rad) {
    return arc.front_rad - (theta_rad - arc.exit_rad) * (arc.front_rad - arc.max_stress_rad) /
                               (arc.max_stress_rad - arc.exit_rad);
  }
  return theta_rad;
}

double normal_stress_pa(const SoilParams& soil, const ContactArc& arc, double rim_radius_m,
                        double width_m, double theta_rad) {
  if (theta_rad > arc.front_rad || theta_rad < arc.exit_rad || arc.entry_rad <= 0.0) return 0.0;
  const double modulus = soil.cohesive_modulus / width_m + soil.frictional_modulus;
  return normal_stress_from_cos_pa(modulus, arc, rim_radius_m,
                                   std::cos(equivalent_angle_rad(arc, theta_rad)));
}

double soil_shear_pa(const SoilParams& soil, double normal_pa, double displacement_m) {
  const double strength = soil.cohesion_pa + normal_pa * std::tan(soil.friction_angle_rad);
  return strength * mobilised(displacement_m, 1.0 / soil.shear_modulus_m);
}

double metal_shear_pa(const SoilParams& soil, double normal_pa, double displacement_m) {
  return normal_pa * std::tan(soil.soil_metal_friction_angle_rad) *
         mobilised(displacement_m, 1.0 / soil.shear_modulus_m);
}

ShearStrength shear_strength(const SoilParams& soil) {
  return {soil.cohesion_pa, std::tan(soil.friction_angle_rad),
          std::tan(soil.soil_metal_friction_angle_rad), soil.shear_modulus_m,
          1.0 / soil.shear_modulus_m};
}

BladeAxes blade_axes(const WheelGeometry& wheel) {
  return {wheel.bladed, std::sin(wheel.blade_inclination_rad),
          std::cos(wheel.blade_inclination_rad)};
}

SurfaceShear rim_shear(const ShearStrength& strength, const WheelGeometry& wheel, int handedness,
                       double normal_pa, double tangential_displacement_m,
                       double lateral_displacement_m) {
  return rim_shear(strength, blade_axes(wheel), handedness, normal_pa, tangential_displacement_m,
                   lateral_displacement_m);
}

SurfaceShear rim_shear(const SoilParams& soil, const WheelGeometry& wheel, int handedness,
                       double normal_pa, double tangential_displacement_m,
                       double lateral_displacement_m) {
  return rim_shear(shear_strength(soil), wheel, handedness, normal_pa, tangential_displacement_m,
                   lateral_displacement_m);
}

double steady_shear_displacement_m(const ContactArc& arc, double shear_radius_m, double slip,
                                   double theta_rad) {
  const double travel_per_radian =
      slip >= 0.0 ? shear_radius_m * (1.0 - slip) : shear_radius_m / (1.0 + slip);
  return shear_radius_m * (arc.entry_rad - theta_rad) -
         travel_per_radian * (std::sin(arc.entry_rad) - std::sin(theta_rad));
}

PlanarForces steady_wheel_forces(const SoilParams& soil, const WheelGeometry& wheel,
                                 double sinkage_m, double slip) {
  PlanarForces forces;
  const double r = wheel.rim_radius_m, rs = wheel.shear_radius_m(), b = wheel.width_m;
  const ContactArc arc = contact_arc(soil, r, sinkage_m, slip);
  const double span = arc.entry_rad - arc.exit_rad;
  if (span <= 0.0) return forces;
  const int samples = wheel.arc_samples;
  const double step = span / samples;
  const int handedness = static_cast<int>(wheel.handedness);
  const ShearStrength strength = shear_strength(soil);
  for (int k = 0; k < samples; ++k) {
    const double theta = arc.entry_rad - (k + 0.5) * step;
    const double sigma = normal_stress_pa(soil, arc, r, b, theta);
    const double j = steady_shear_displacement_m(arc, rs, slip, theta);
    const SurfaceShear tau = rim_shear(strength, wheel, handedness, sigma, j, 0.0);
    const double area = step * b;
    forces.drawbar_pull_n +=
        (tau.tangential_pa * rs * std::cos(theta) - sigma * r * std::sin(theta)) * area;
    forces.vertical_load_n +=
        (sigma * r * std::cos(theta) + tau.tangential_pa * rs * std::sin(theta)) * area;
    forces.lateral_n += tau.lateral_pa * rs * area;
    forces.driving_torque_nm += tau.tangential_pa * rs * rs * area;
  }
  return forces;
}

double equilibrium_sinkage_m(const SoilParams& soil, const WheelGeometry& wheel, double load_n,
                             double slip) {
  if (!(load_n >= 0.0) || !std::isfinite(load_n)) {
    std::ostringstream message;
    message << "equilibrium_sinkage_m: the load must be a finite number >= 0 N, got " << load_n;
    throw std::invalid_argument(message.str());
  }
  double low = 0.0, high = wheel.rim_radius_m;
  if (steady_wheel_forces(soil, wheel, high, slip).vertical_load_n < load_n) {
    std::ostringstream message;
    message << "equilibrium_sinkage_m: soil '" << soil.name << "' cannot carry " << load_n
            << " N on this wheel before it sinks to its axle; use a lighter load or a wider wheel";
    throw std::invalid_argument(message.str());
  }
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double middle = 0.5 * (low + high);
    if (steady_wheel_forces(soil, wheel, middle, slip).vertical_load_n < load_n) {
      low = middle;
    } else {
      high = middle;
    }
  }
  return 0.5 * (low + high);
}

double passive_earth_coefficient(const SoilParams& soil) {
  return std::pow(std::tan(std::numbers::pi / 4.0 + soil.friction_angle_rad / 2.0), 2);
}

double sidewall_resistance_n(const SoilParams& soil, double rim_radius_m, double sinkage_m) {
  return sidewall_resistance_n(soil, passive_earth_coefficient(soil), rim_radius_m, sinkage_m);
}

// Over the segment below the surface, h = r − z from the centre: its area
//   A = r² acos(h/r) − h √(r² − h²)
// and the integral of the depth over it, ∫_h^r (y − h)·2√(r² − y²) dy = ⅔ (r² − h²)^(3/2) − h A, so
//   F = 2c√N_φ · A + ρ g N_φ · (⅔ (r² − h²)^(3/2) − h A).
// Both differences cancel as z → 0; below z = 1e-3·r their leading terms, A ≈ (4/3)√(2r) z^(3/2)
// and (8/15)√(2r) z^(5/2) (the segment's parabola; relative error ≈ z/r), are used instead.
double sidewall_resistance_n(const SoilParams& soil, double passive, double rim_radius_m,
                             double sinkage_m) {
  const double z = std::clamp(sinkage_m, 0.0, rim_radius_m);
  if (z <= 0.0) return 0.0;
  const double r = rim_radius_m, h = r - z;
  double area = 0.0, depth_moment = 0.0;
  if (z < 1e-3 * r) {
    const double root = std::sqrt(2.0 * r * z);  // √(2r)·z^(1/2)
    area = 4.0 / 3.0 * root * z;
    depth_moment = 8.0 / 15.0 * root * z * z;
  } else {
    const double half_chord = std::sqrt(z * (2.0 * r - z));  // √(r² − h²) without cancelling
    area = r * r * std::acos(h / r) - h * half_chord;
    depth_moment = 2.0 / 3.0 * half_chord * half_chord * half_chord - h * area;
  }
  return 2.0 * soil.cohesion_pa * std::sqrt(passive) * area +
         soil.bulk_density_kgpm3 * soil.gravity_mps2 * passive * depth_moment;
}

}  // namespace marsokhod::sim::soil
