// Soil and wheel parameters of the terramechanics model (docs/simulator.md, "Soft soil").
//
// Units are SI throughout: the published tables give k_c in kN/m^(n+1), k_φ in kN/m^(n+2) and c in
// kPa; the structs hold N/m^(n+1), N/m^(n+2) and Pa. Angles are radians.
//
// Bekker pressure–sinkage:        p = (k_c / b + k_φ) · z^n,      n = n0 + n1·|s|   (Ding et al.)
// Janosi–Hanamoto shear:          τ = (c + σ tan φ) · (1 − e^(−j/K))
// Soil–metal friction (blades):   τ = σ tan δ · (1 − e^(−j/K))
// Wong–Reece angle of maximum normal stress: θm = (c1 + c2·s) · θ1
#pragma once

#include <string>

namespace marsokhod::sim::soil {

struct SoilParams {
  std::string name = "sand";
  double sinkage_exponent = 1.1;           // n0, Bekker's n at zero slip
  double slip_sinkage_exponent = 0.0;      // n1: n = n0 + n1·|s| (Ding et al. 2011)
  double cohesive_modulus = 0.99e3;        // k_c, N/m^(n+1)
  double frictional_modulus = 1528.43e3;   // k_φ, N/m^(n+2)
  double cohesion_pa = 1.04e3;             // c
  double friction_angle_rad = 0.48869219;  // φ (28°)
  double shear_modulus_m = 0.010;          // K, Janosi–Hanamoto shear deformation modulus
  double soil_metal_friction_angle_rad = 0.26179939;  // δ, along a blade (15°)
  double max_stress_angle_c1 = 0.4;                   // θm = (c1 + c2·s)·θ1 (Wong–Reece)
  double max_stress_angle_c2 = 0.15;
  double bulk_density_kgpm3 = 1600.0;  // ρ, for the sidewall's passive earth pressure
  double gravity_mps2 = 9.81;
  double repose_angle_rad = 0.48869219;  // slopes of the grid relax to this angle
  // Of the soil a wheel presses down, the share pushed aside to the patch's rim; the rest is
  // compacted in place (the grid's compaction counter).
  double displaced_fraction = 0.5;
  // A rim rising out of the rut it pressed unloads elastically: its effective sinkage falls by this
  // ratio times the gap that opens under it (Bekker's curve is for first loading only; SCM and
  // Wong's repetitive-loading tests unload far stiffer). Not from a table: 10.
  double unloading_stiffness_ratio = 10.0;
  // Along the rim (the tangential shear state), soil that unloaded and is loaded the same way
  // again reloads along the stiff line it unloaded on until it is back where it began to unload,
  // and only then follows Janosi–Hanamoto's curve (Masing's rule for cyclic shear, in the form of
  // Wong's repetitive loading: unloading and reloading share one line). false (the default): it
  // reloads along the curve from the share it fell to, as from fresh soil, and a chassis' jitter
  // of a millimetre wipes a still wheel's grip (docs/simulator.md, "The anchors' jitter"). Opt-in
  // (a scenario's [terrain] shear_reload_memory, slope-sweep --shear-reload-memory) until every
  // scenario holds with it on every unit: with it, front-wheel-walking-slope-slant-on stalls on
  // units 18 and 29 of 1–40.
  bool tangential_reload_memory = false;
  // Vertical damping of the contact, per unit area: σ_d = R·v, v the rim's sinking speed (SCM's
  // damping R, as Chrono's SCM terrain has it; 3e4 Pa·s/m is its demonstrations' value, not a
  // soil measurement). It keeps a rover from bouncing on the soil's elastic unloading.
  double vertical_damping_pa_s_per_m = 3e4;
  // Of the soil a blade groove lifts out while the wheel slips, the share that does not fall back
  // into the rut but lands behind the wheel (excavation).
  double excavation_fraction = 1.0;
};

// Throws std::invalid_argument naming the soil, the parameter, its value and the allowed range.
void validate(const SoilParams& soil);

// Wong's dry sand (J. Y. Wong, Theory of Ground Vehicles, table of terrain values, from the Land
// Locomotion Laboratory): n 1.1, k_c 0.99 kN/m^(n+1), k_φ 1528.43 kN/m^(n+2), c 1.04 kPa, φ 28°.
// K: Wong's range for sand is 10–25 mm; we take 10 mm. At 25 mm the steady drawbar pull of a
// Marsokhod wheel stays below 0.13 of its load at any slip (a 7° climb), at 10 mm it reaches 0.24
// (13.5°); neither reaches [KG92]'s 20° by driving (docs/simulator.md). Not in the table, and said
// so in docs/simulator.md: δ = 15° (Potyondy 1961, δ/φ ≈ 0.54 for dry sand on smooth steel), ρ =
// 1600 kg/m³, the angle of repose = φ, n1 = 0 (no published slip sinkage for this sand), c1 = 0.4,
// c2 = 0.15 (Wong–Reece's θm, as used by Ishigami et al. 2007).
SoilParams dry_sand();

// Lunar soil as tabulated by Ding et al. (2015, J. Field Robotics 32(6), Table I, after Wong and
// Bekker's lunar-surface estimates): n 1.0, k_c 1.4 kN/m^(n+1), k_φ 820 kN/m^(n+2), c 0.17 kPa,
// φ 35°, K 18 mm; weight density 2470 N/m³ at lunar gravity 1.625 m/s² (ρ = 1520 kg/m³).
SoilParams lunar_soil();

enum class BladeHandedness { kRight = 1, kLeft = -1 };

// A rigid wheel with inclined blades. rim_radius_m carries the pressure (the soil fills the grooves
// between the blades: r = 0.115 m "on granules", chapter 3.1); the blades shear the soil at
// rim_radius_m + blade_height_m (0.125 m, the radius on solid terrain).
//
// The blades cross the rim at blade_inclination_rad to the axle. Handedness, seen in the wheel's
// contact patch with x its rolling direction and y its axle (to the rover's left): kRight leans
// each blade so that its +y end lies ahead (+x) of its −y end, kLeft the mirror image.
struct WheelGeometry {
  double rim_radius_m = 0.115;
  double blade_height_m = 0.010;
  double width_m = 0.15;
  double blade_inclination_rad = 0.240;
  BladeHandedness handedness = BladeHandedness::kRight;
  bool bladed = true;  // false: a smooth rim sheared by the soil's own strength in every direction
  int arc_samples = 24;  // samples over the contact angle
  int lanes = 3;         // lanes across the width

  double shear_radius_m() const { return rim_radius_m + blade_height_m; }
};

// Throws std::invalid_argument naming the parameter, its value and the allowed range.
void validate(const WheelGeometry& wheel);

}  // namespace marsokhod::sim::soil
