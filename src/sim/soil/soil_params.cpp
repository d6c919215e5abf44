#include "sim/soil/soil_params.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace marsokhod::sim::soil {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

// Rejects a value outside [min, max] (or NaN) with the owner, the name, the value and the range.
void require_range(const std::string& owner, const char* name, double value, double min, double max,
                   const char* unit) {
  if (std::isfinite(value) && value >= min && value <= max) return;
  std::ostringstream message;
  message << owner << ": " << name << " must be within [" << min << ", " << max << "] " << unit
          << ", got " << value;
  throw std::invalid_argument(message.str());
}

void require_count(const char* name, int value, int min, int max) {
  if (value >= min && value <= max) return;
  std::ostringstream message;
  message << "wheel: " << name << " must be within [" << min << ", " << max << "], got " << value;
  throw std::invalid_argument(message.str());
}

}  // namespace

void validate(const SoilParams& soil) {
  const std::string owner = "soil '" + soil.name + "'";
  const double half_pi = std::numbers::pi / 2.0;
  require_range(owner, "sinkage_exponent (n0)", soil.sinkage_exponent, 0.1, 3.0, "");
  require_range(owner, "slip_sinkage_exponent (n1)", soil.slip_sinkage_exponent, 0.0, 2.0, "");
  require_range(owner, "cohesive_modulus (k_c)", soil.cohesive_modulus, 0.0, 1e9, "N/m^(n+1)");
  require_range(owner, "frictional_modulus (k_phi)", soil.frictional_modulus, 0.0, 1e12,
                "N/m^(n+2)");
  if (soil.cohesive_modulus + soil.frictional_modulus <= 0.0) {
    throw std::invalid_argument(owner + ": k_c and k_phi are both 0; the soil would carry no load");
  }
  require_range(owner, "cohesion_pa (c)", soil.cohesion_pa, 0.0, 1e7, "Pa");
  require_range(owner, "friction_angle_rad (phi)", soil.friction_angle_rad, 0.0, 1.2, "rad");
  require_range(owner, "shear_modulus_m (K)", soil.shear_modulus_m, 1e-5, 1.0, "m");
  require_range(owner, "soil_metal_friction_angle_rad (delta)", soil.soil_metal_friction_angle_rad,
                0.0, 1.2, "rad");
  require_range(owner, "max_stress_angle_c1", soil.max_stress_angle_c1, 0.0, 1.0, "");
  require_range(owner, "max_stress_angle_c2", soil.max_stress_angle_c2, 0.0, 1.0, "");
  require_range(owner, "bulk_density_kgpm3", soil.bulk_density_kgpm3, 1.0, 1e4, "kg/m^3");
  require_range(owner, "gravity_mps2", soil.gravity_mps2, 0.0, 100.0, "m/s^2");
  require_range(owner, "repose_angle_rad", soil.repose_angle_rad, 0.01, half_pi - 0.01, "rad");
  require_range(owner, "displaced_fraction", soil.displaced_fraction, 0.0, 1.0, "");
  require_range(owner, "excavation_fraction", soil.excavation_fraction, 0.0, 1.0, "");
  require_range(owner, "vertical_damping_pa_s_per_m", soil.vertical_damping_pa_s_per_m, 0.0, 1e9,
                "Pa s/m");
  require_range(owner, "unloading_stiffness_ratio", soil.unloading_stiffness_ratio, 1.0, 1e4, "");
}

SoilParams dry_sand() { return SoilParams{}; }

SoilParams lunar_soil() {
  SoilParams soil;
  soil.name = "lunar soil";
  soil.sinkage_exponent = 1.0;
  soil.cohesive_modulus = 1.4e3;
  soil.frictional_modulus = 820e3;
  soil.cohesion_pa = 0.17e3;
  soil.friction_angle_rad = 35.0 * kRadPerDeg;
  soil.shear_modulus_m = 0.018;
  soil.soil_metal_friction_angle_rad = 0.54 * 35.0 * kRadPerDeg;
  soil.bulk_density_kgpm3 = 2470.0 / 1.625;
  soil.gravity_mps2 = 1.625;
  soil.repose_angle_rad = 35.0 * kRadPerDeg;
  return soil;
}

void validate(const WheelGeometry& wheel) {
  const std::string owner = "wheel";
  require_range(owner, "rim_radius_m", wheel.rim_radius_m, 0.01, 5.0, "m");
  require_range(owner, "blade_height_m", wheel.blade_height_m, 0.0, wheel.rim_radius_m, "m");
  require_range(owner, "width_m", wheel.width_m, 0.005, 5.0, "m");
  require_range(owner, "blade_inclination_rad", wheel.blade_inclination_rad, -1.2, 1.2, "rad");
  if (wheel.handedness != BladeHandedness::kRight && wheel.handedness != BladeHandedness::kLeft) {
    throw std::invalid_argument("wheel: handedness must be kRight or kLeft");
  }
  require_count("arc_samples", wheel.arc_samples, 4, 256);
  require_count("lanes", wheel.lanes, 1, 16);
}

}  // namespace marsokhod::sim::soil
