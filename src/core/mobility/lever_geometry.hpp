// Figure 3.3 and the chapter 5 table: the triangle joint – exterior axle – center axle of one
// lever, its rates (Lemma 5.3) and the joint bounds (5.3).
//
//   γf = −p6,  γr = +p7                                bending of the front / rear joint [rad]
//   c = sqrt(a² + b² − 2ab·cos γ)                      clearance of exterior to center axle [m]
//   α = acos((b² + c² − a²)/(2bc))                     inclination of the lever [rad]
//
// a = joint_to_exterior_axle_m (side between joint and exterior axle), b = center_axle_to_joint_m;
// γ is the angle at the joint, α the angle at the center axle, c the side opposite γ.
// Lemma 5.3, with φ the angle between side a and the height h onto c:
//   ∂c/∂γ = ab·sin γ / c                     [m/rad]
//   ∂φ/∂γ = b(b − a·cos γ)/c²                [rad/rad]   (φ = π/2 − the angle at the exterior axle)
//   ∂(γ − φ)/∂γ = a(a − b·cos γ)/c² = −∂α/∂γ [rad/rad]   (γ − φ = π/2 − α)
// At γ = acos(a/b) the angle at the exterior axle is a right angle: c = sqrt(b² − a²) = 0.3867 m
// and α = asin(a/b) = 0.3587 rad (the table's 0.359); at γ = 2.55, c = 0.5395 m.
//
// (5.3): p6 ∈ [p6_min, p6_max] = [−2.55, −acos(a/b)], p7 ∈ [p7_min, p7_max] = [acos(a/b), 2.55],
// read from JointParams (which round acos(a/b) = 1.21206 to 1.2121).
#pragma once

#include "core/params.hpp"

namespace marsokhod::mobility {

// Throws std::invalid_argument naming the field unless a, b, r are finite and > 0 and a < b
// (acos(a/b) of (5.3) needs a < b).
void validate(const GeometryParams& geometry);

// Throws std::invalid_argument naming the field unless both (5.3) intervals are finite and
// non-empty, μ and the tolerance are finite and > 0.
void validate(const JointParams& joints);

double front_joint_bending_rad(double front_joint_position_rad);  // γf = −p6
double rear_joint_bending_rad(double rear_joint_position_rad);    // γr = +p7

// acos(a/b): the bending of a contracted joint (lever vertical, Remark 3.1's 1.2121 rad).
double contracted_bending_rad(const GeometryParams& geometry);

// c(γ) [m], law of cosines.
double axle_clearance_m(double bending_rad, const GeometryParams& geometry);

// α(γ) [rad]; the acos argument is clamped to [−1, 1] against rounding.
double lever_inclination_rad(double bending_rad, const GeometryParams& geometry);

// Lemma 5.3's rates at γ: ∂c/∂γ [m/rad], ∂φ/∂γ and ∂(γ − φ)/∂γ [rad/rad].
struct LeverRates {
  double clearance_m_per_rad = 0.0;  // ab·sin γ / c
  double exterior_angle_rate = 0.0;  // b(b − a·cos γ)/c²
  double joint_angle_rate = 0.0;     // a(a − b·cos γ)/c² = −∂α/∂γ
};
LeverRates lever_rates(double bending_rad, const GeometryParams& geometry);

// One lever at a joint position: γ, c and α together.
struct Lever {
  double bending_rad = 0.0;
  double clearance_m = 0.0;
  double inclination_rad = 0.0;
};
Lever front_lever(double front_joint_position_rad, const GeometryParams& geometry);
Lever rear_lever(double rear_joint_position_rad, const GeometryParams& geometry);

// The pitch of the center unit, ½(αf − αr) (Figure 3.3) [rad].
double center_unit_pitch_rad(double front_joint_position_rad, double rear_joint_position_rad,
                             const GeometryParams& geometry);

// (5.3) for one joint.
struct JointBounds {
  double min_rad = 0.0;
  double max_rad = 0.0;
  bool contains(double position_rad) const {
    return min_rad <= position_rad && position_rad <= max_rad;
  }
  double clamp(double position_rad) const;
};
JointBounds front_joint_bounds(const JointParams& joints);  // [p6_min, p6_max], validated
JointBounds rear_joint_bounds(const JointParams& joints);   // [p7_min, p7_max], validated

}  // namespace marsokhod::mobility
