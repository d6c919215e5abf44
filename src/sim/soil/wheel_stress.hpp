// The Wong–Reece stress distribution under a rigid wheel (J. Y. Wong and A. R. Reece, "Prediction
// of rigid wheel performance based on the analysis of soil–wheel stresses", J. Terramechanics 4,
// 1967), pure functions of the soil, the wheel and its state.
//
// Motion frame: x the wheel's rolling direction, y its axle, z up; θ measured at the wheel's centre
// from straight down, positive ahead. The rim touches the soil over θ2 ≤ θ ≤ θ1:
//   entry angle            θ1 = acos(1 − z / r)                        (z the sinkage, r the rim)
//   exit angle             θ2 ∈ [−θ1, 0]: 0 behind a rolling wheel (its rut, no rebound in dry
//                          sand), −θ1 under a wheel that sank straight down (from the grid)
//   max. normal stress     θm = (c1 + c2·s)·(θ1 + θ2): Wong–Reece's (c1 + c2·s)·θ1 for θ2 = 0; for
//                          θ2 = −θ1 it is 0 and σ is symmetric, Bekker's plate pressure under
//                          every point of the rim (our generalisation, so a still wheel is not
//                          pushed backward)
//   normal stress          σ(θ) = (k_c/b + k_φ)·r^n·(cos θ* − cos θ1)^n,
//                          θ* = θ for θ ≥ θm, θ* = θ1 − (θ − θ2)(θ1 − θm)/(θm − θ2) behind θm
//   sinkage exponent       n = n0 + n1·|s|                             (Ding et al. 2011)
//   shear                  τ = (c + σ tan φ)(1 − e^(−j/K))             (Janosi–Hanamoto)
// with the shear displacement j of the blade tips (radius r_s = r + blade height) against the soil.
// Forces on the wheel per sample of width Δb and angle Δθ:
//   F_x = (τ_t r_s cos θ − σ r sin θ) Δθ Δb,  F_z = (σ r cos θ + τ_t r_s sin θ) Δθ Δb,
//   F_y = τ_y r_s Δθ Δb,                       torque on the wheel about its axle −τ_t r_s² Δθ Δb.
//
// Slip s = (r_s ω − v) / max(|r_s ω|, |v|): Wong's slip 1 − v/(r_s ω) when driving, his skid
// r_s ω / v − 1 when braked; regularised below 1 cm/s so that it is defined at rest. It enters only
// through n and θm; the shear itself comes from the displacement j (wheel_soil.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/soil/fast_math.hpp"
#include "sim/soil/soil_params.hpp"
#include "sim/soil/wide.hpp"

namespace marsokhod::sim::soil {

// Below this speed the slip's denominator is held, so that s is continuous at rest.
inline constexpr double kSlipSpeedFloorMps = 0.01;

double regularised_slip(double rim_speed_mps, double travel_speed_mps);

struct ContactArc {
  double entry_rad = 0.0;         // θ1
  double cos_entry = 1.0;         // cos θ1 = 1 − z/r
  double max_stress_rad = 0.0;    // θm
  double exit_rad = 0.0;          // θ2
  double sinkage_exponent = 1.0;  // n
  // Where the rim meets the soil ahead, θ1 unless the soil there lies lower than undisturbed (a
  // rut the wheel rolls back into): the arc's stresses act on [θ2, θf], Bekker's depth measured
  // from θ1's level all the same.
  double front_rad = 0.0;
};

// The arc of a rim of radius rim_radius_m sunk sinkage_m (clamped to [0, r]) at slip s, the soil
// behind it reaching up to exit_rad (clamped to [−θ1, 0]), ahead up to front_rad (clamped to
// [0, θ1]; the default is θ1).
ContactArc contact_arc(const SoilParams& soil, double rim_radius_m, double sinkage_m, double slip,
                       double exit_rad = 0.0,
                       double front_rad = std::numeric_limits<double>::infinity());
// The same with θ1 as the caller already took it, std::acos(1 − clamp(sinkage_m, 0, r)/r) (the
// soil's lane search does: one arc cosine a lane instead of two).
ContactArc contact_arc_at_entry(const SoilParams& soil, double rim_radius_m, double sinkage_m,
                                double slip, double exit_rad, double front_rad, double entry_rad);

// σ(θ) in Pa; 0 outside the arc. width_m is the wheel's full width b (Bekker's k_c/b).
double normal_stress_pa(const SoilParams& soil, const ContactArc& arc, double rim_radius_m,
                        double width_m, double theta_rad);

// θ* of normal_stress_pa at θ within the arc: θ ahead of θm, the front's profile compressed onto
// [θ2, θm] behind it. It is linear in θ on either side of θm, so samples evenly spaced in θ have
// evenly spaced θ* there (wheel_soil.cpp steps their cosines by rotation).
double equivalent_angle_rad(const ContactArc& arc, double theta_rad);

// σ from cos θ*: (k_c/b + k_φ)·(r·max(cos θ* − cos θ1, 0))^n, the power as exp(n·ln x) (within a
// few units in the last place of std::pow, at a third of its cost; n = 1 exactly is x itself; the
// exponential exp_nonpositive, fast_math.hpp).
inline double normal_stress_from_cos_pa(double modulus_pa, const ContactArc& arc,
                                        double rim_radius_m, double cos_equivalent);
// The same over an array in place (cosines in, stresses out), two samples' exponentials at a
// time: the same bits as one by one.
inline void normal_stresses_from_cos_pa(double modulus_pa, const ContactArc& arc,
                                        double rim_radius_m, double* values, int count);

// Signed Janosi–Hanamoto shear of soil on soil and of soil on metal, for a signed displacement.
double soil_shear_pa(const SoilParams& soil, double normal_pa, double displacement_m);
double metal_shear_pa(const SoilParams& soil, double normal_pa, double displacement_m);

// The shear stress on the rim in the surface's own axes (t along the rim's rolling direction at
// the bottom, y along the axle), for the displacement (j_t, j_y) of the soil's pull on the wheel.
// Smooth rim: the soil's strength along the displacement. Bladed rim, blade b = (h sin i, cos i)
// and its normal n_b = (cos i, −h sin i) in (t, y), h = ±1 the handedness in the motion frame:
// across the blade τ_n = soil_shear(j·n_b), along it τ_b = metal_shear(j·b); τ = τ_n n_b + τ_b b.
struct SurfaceShear {
  double tangential_pa = 0.0;
  double lateral_pa = 0.0;
};
// The soil's shear constants, their tangents taken once (a wheel's contact keeps one).
struct ShearStrength {
  double cohesion_pa = 0.0;
  double tan_friction = 0.0;        // tan φ
  double tan_metal_friction = 0.0;  // tan δ
  double shear_modulus_m = 0.01;    // K
  double inverse_shear_modulus_per_m = 100.0;  // 1/K, so that the hot loop multiplies
};
ShearStrength shear_strength(const SoilParams& soil);
SurfaceShear rim_shear(const ShearStrength& strength, const WheelGeometry& wheel, int handedness,
                       double normal_pa, double tangential_displacement_m,
                       double lateral_displacement_m);
// The blade's direction cosines, taken once per wheel: sin i and cos i of its inclination.
struct BladeAxes {
  bool bladed = true;
  double sin_inclination = 0.0;
  double cos_inclination = 1.0;
};
BladeAxes blade_axes(const WheelGeometry& wheel);
// The same in two parts, so that a loop can take the exponentials of all its samples first: the
// blade's axes in (t, y) for a handedness — b = (h sin i, cos i) along it, n_b = (cos i, −h sin i)
// across it — and the bladed rim's shear from the signed mobilised shares across and along it,
// 1 − e^(−|j·n_b|/K) and 1 − e^(−|j·b|/K) signed as their displacements.
struct BladeFrame {
  double along_t = 0.0, along_y = 1.0, across_t = 1.0, across_y = 0.0;
  double across_displacement_m(double jt, double jy) const { return jt * across_t + jy * across_y; }
  double along_displacement_m(double jt, double jy) const { return jt * along_t + jy * along_y; }
};
inline BladeFrame blade_frame(const BladeAxes& blades, int handedness);
inline SurfaceShear bladed_shear(const ShearStrength& strength, const BladeFrame& blade,
                                 double normal_pa, double across_share, double along_share);
// (Inline below: they run for every sample of every lane of every wheel.)
inline SurfaceShear rim_shear(const ShearStrength& strength, const BladeAxes& blades,
                              int handedness, double normal_pa, double tangential_displacement_m,
                              double lateral_displacement_m);
SurfaceShear rim_shear(const SoilParams& soil, const WheelGeometry& wheel, int handedness,
                       double normal_pa, double tangential_displacement_m,
                       double lateral_displacement_m);

// Steady-state longitudinal displacement at θ for slip s (Wong–Reece):
//   j(θ) = r_s (θ1 − θ) − (v/ω)(sin θ1 − sin θ),  v/ω = r_s (1 − s) for s ≥ 0, r_s / (1 + s) below.
double steady_shear_displacement_m(const ContactArc& arc, double shear_radius_m, double slip,
                                   double theta_rad);

// Sums of a wheel at steady slip s (no lateral slip), integrated by the midpoint rule over
// wheel.arc_samples samples of the arc, in the motion frame.
struct PlanarForces {
  double drawbar_pull_n = 0.0;     // F_x
  double vertical_load_n = 0.0;    // F_z, the load the soil carries
  double lateral_n = 0.0;          // F_y (from inclined blades)
  double driving_torque_nm = 0.0;  // the torque the soil resists the wheel's turning with
};
PlanarForces steady_wheel_forces(const SoilParams& soil, const WheelGeometry& wheel,
                                 double sinkage_m, double slip);

// The sinkage at which the steady wheel carries load_n at slip s (bisection). Throws
// std::invalid_argument for a negative load or one the soil cannot carry above the axle.
double equilibrium_sinkage_m(const SoilParams& soil, const WheelGeometry& wheel, double load_n,
                             double slip);

// The sidewall's bulldozing resistance: Rankine's passive earth pressure
//   p(d) = ρ g d N_φ + 2 c √N_φ,  N_φ = tan²(45° + φ/2),
// over the wheel's submerged side face (a circular segment of depth z), in N.
double sidewall_resistance_n(const SoilParams& soil, double rim_radius_m, double sinkage_m);
// N_φ, and the same resistance with it taken once.
double passive_earth_coefficient(const SoilParams& soil);
double sidewall_resistance_n(const SoilParams& soil, double passive_coefficient,
                             double rim_radius_m, double sinkage_m);

namespace detail {

// Janosi–Hanamoto's mobilised share 1 − e^(−|j|/K), signed as j (exp_nonpositive: fast_math.hpp).
inline double mobilised(double displacement_m, double inverse_shear_modulus_per_m) {
  const double share =
      1.0 - exp_nonpositive(-std::abs(displacement_m) * inverse_shear_modulus_per_m);
  return displacement_m < 0.0 ? -share : share;
}

// The same for two displacements at once (the blade's across and along), the same bits.
inline DoublePair mobilised(DoublePair displacement_m, double inverse_shear_modulus_per_m) {
  const DoublePair magnitude = {std::abs(displacement_m[0]), std::abs(displacement_m[1])};
  const DoublePair share = 1.0 - exp_nonpositive(-magnitude * inverse_shear_modulus_per_m);
  return displacement_m < 0.0 ? -share : share;
}

// The depth r·(cos θ* − cos θ1) Bekker's pressure is taken at, 0 outside the arc.
inline double bekker_depth_m(const ContactArc& arc, double rim_radius_m, double cos_equivalent) {
  return rim_radius_m * std::max(cos_equivalent - arc.cos_entry, 0.0);
}

}  // namespace detail

inline double normal_stress_from_cos_pa(double modulus_pa, const ContactArc& arc,
                                        double rim_radius_m, double cos_equivalent) {
  const double depth = detail::bekker_depth_m(arc, rim_radius_m, cos_equivalent);
  if (depth <= 0.0) return 0.0;
  const double n = arc.sinkage_exponent;
  if (n == 1.0) return modulus_pa * depth;
  const double logarithm =
      depth >= std::numeric_limits<double>::min() ? log_positive(depth) : std::log(depth);
  const double exponent = n * logarithm;  // < 0 while the depth is under 1 m
  return modulus_pa * (exponent <= 0.0 ? exp_nonpositive(exponent) : std::exp(exponent));
}

inline void normal_stresses_from_cos_pa(double modulus_pa, const ContactArc& arc,
                                        double rim_radius_m, double* values, int count) {
  const double n = arc.sinkage_exponent;
  int k = 0;
  if (n != 1.0 && wide::available()) {  // four at a time first: the same bits
    k = wide::bekker_stresses(modulus_pa, arc.cos_entry, rim_radius_m, n, values, count);
  }
  for (; k + 1 < count && n != 1.0; k += 2) {
    const double first = detail::bekker_depth_m(arc, rim_radius_m, values[k]);
    const double second = detail::bekker_depth_m(arc, rim_radius_m, values[k + 1]);
    constexpr double kNormal = std::numeric_limits<double>::min();  // log_positive's domain
    if (!(first >= kNormal && second >= kNormal)) break;  // the rest one by one
    const DoublePair exponent = n * log_positive(DoublePair{first, second});
    if (!(exponent[0] <= 0.0 && exponent[1] <= 0.0)) break;
    const DoublePair power = exp_nonpositive(exponent);
    values[k] = modulus_pa * power[0];
    values[k + 1] = modulus_pa * power[1];
  }
  for (; k < count; ++k) {
    values[k] = normal_stress_from_cos_pa(modulus_pa, arc, rim_radius_m, values[k]);
  }
}

inline BladeFrame blade_frame(const BladeAxes& blades, int handedness) {
  const double h = handedness < 0 ? -1.0 : 1.0;
  const double sin_i = blades.sin_inclination, cos_i = blades.cos_inclination;
  return {h * sin_i, cos_i, cos_i, -h * sin_i};
}

inline SurfaceShear bladed_shear(const ShearStrength& strength, const BladeFrame& blade,
                                 double normal_pa, double across_share, double along_share) {
  const double soil_strength = strength.cohesion_pa + normal_pa * strength.tan_friction;
  const double across = soil_strength * across_share;
  const double along = normal_pa * strength.tan_metal_friction * along_share;
  return {across * blade.across_t + along * blade.along_t,
          across * blade.across_y + along * blade.along_y};
}

inline SurfaceShear rim_shear(const ShearStrength& strength, const BladeAxes& blades,
                              int handedness, double normal_pa, double tangential_displacement_m,
                              double lateral_displacement_m) {
  const double jt = tangential_displacement_m, jy = lateral_displacement_m;
  const double soil_strength = strength.cohesion_pa + normal_pa * strength.tan_friction;
  const double inverse_K = strength.inverse_shear_modulus_per_m;
  if (!blades.bladed) {
    // Isotropic: the soil's strength along the displacement's own direction.
    const double length = std::hypot(jt, jy);
    if (length <= 0.0) return {};
    const double tau = soil_strength * detail::mobilised(length, inverse_K);
    return {tau * jt / length, tau * jy / length};
  }
  const BladeFrame blade = blade_frame(blades, handedness);
  return bladed_shear(strength, blade, normal_pa,
                      detail::mobilised(blade.across_displacement_m(jt, jy), inverse_K),
                      detail::mobilised(blade.along_displacement_m(jt, jy), inverse_K));
}

}  // namespace marsokhod::sim::soil
