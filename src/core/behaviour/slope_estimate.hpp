// Chapter 6.2.1: the slope of the terrain along the rover's x1 axis from the accelerometer.
//
//   ḡ^k = λ g^(k−1) + (1 − λ) a^k / ‖a^k‖,   g^k = ḡ^k / ‖ḡ^k‖,   g⁰ = (0, 0, −1)
//   σ = acos(g1) − π/2 + (αr − αf)/2
//
// a^k [m/s²] is the accelerometer reading converted by (3.5) in the sensor frame (x1 forward,
// x2 left, x3 up); at rest it points along gravity, so on flat ground a = (0, 0, −9.81) and
// g = g⁰. λ = FilterParams::gravity_lambda per cycle, close to 1. αf, αr are the lever
// inclinations of the table in chapter 5 (from the mobility geometry, passed in here): their
// half difference corrects for the center unit, which carries the sensor, pitching against the
// line of the exterior axles.
//
// Sign convention: nose up by θ on a slope tilts x1 upward, so gravity gains a component
// against x1: a = 9.81 (−sin θ, 0, −cos θ), g1 = −sin θ < 0, acos(g1) = π/2 + θ and σ = θ > 0
// (with αf = αr). Hence a1 < 0 means nose up, σ > 0 means driving uphill (6.2.2's reading),
// and a1 > 0 nose down, σ < 0.
#pragma once

#include <array>

namespace marsokhod::behaviour {

using Vector3 = std::array<double, 3>;

// g⁰: the rover starts assuming flat ground.
inline constexpr Vector3 kInitialGravityDirection{0.0, 0.0, -1.0};

// One step of the gravity filter: g^k from g^(k−1) and a^k. λ in [0, 1) (0: no filtering).
// If ḡ^k vanishes (only possible for λ ≤ 1/2 and a^k exactly against g^(k−1)) the new reading's
// direction a^k/‖a^k‖ is taken. Throws std::invalid_argument if an input is not finite, a^k is
// the zero vector (no direction to learn from: a sensor fault, or free fall), g^(k−1) is the
// zero vector, or λ is outside [0, 1).
Vector3 next_gravity_direction(const Vector3& previous_direction, const Vector3& acceleration_mps2,
                               double lambda);

// σ [rad] from a unit gravity direction g and the lever inclinations αf, αr [rad]. g1 is
// clamped into [−1, 1] against rounding. Throws std::invalid_argument if an input is not
// finite.
double terrain_slope_rad(const Vector3& gravity_direction, double front_lever_inclination_rad,
                         double rear_lever_inclination_rad);

}  // namespace marsokhod::behaviour
