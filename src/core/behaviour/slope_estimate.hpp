// Chapter 6.2.1: the slope of the terrain along the rover's x1 axis from the accelerometer.
//
//   ā^k = λ ā^(k−1) + (1 − λ) a^k,   g^k = ā^k / ‖ā^k‖,   ā⁰ = (0, 0, −9.81 m/s²)
//   σ = acos(g1) − π/2 + (αr − αf)/2
//
// a^k [m/s²] is the accelerometer reading converted by (3.5) in the sensor frame (x1 forward,
// x2 left, x3 up); at rest it points along gravity, so on flat ground a = (0, 0, −9.81) and
// g = (0, 0, −1). λ = FilterParams::gravity_lambda per cycle, close to 1. αf, αr are the lever
// inclinations of the table in chapter 5 (from the mobility geometry, passed in here): their
// half difference corrects for the center unit, which carries the sensor, pitching against the
// line of the exterior axles.
//
// Averaged, then normalised — not as the thesis prints it, ḡ^k = λ g^(k−1) + (1 − λ) a^k/‖a^k‖,
// each reading normalised before the average. While driving the accelerometer reads gravity
// plus the chassis' accelerations, whose mean is zero; the mean of the readings is gravity, but
// the mean of their directions is not: the direction is a convex function of a vertical bump, so
// bumps tilt the averaged direction away from the vertical. On loose sand (the vertical reading
// varies by 3 m/s², σ) this made σ read 2.3° steep on a 20° slope, beyond the chassis' true
// 21° pitch, and moved the slant bound γ(σ) of (6.4) by 0.045 rad. A bump of ±3 m/s² on a 20°
// reading, half the time each way: the thesis' average gives 21.86°, the mean of the readings
// 20° exactly (tested).
//
// The lever correction low-passed like the readings (SlopeEstimate; not in the thesis, which adds
// (αr − αf)/2 as it stands). The centre unit's pitch against the line of the exterior axles
// changes as fast as a joint bends; the filtered gravity follows it with the filter's lag (1.6 s)
// while the unfiltered correction does not, and on flat ground the difference read as slope:
// front-wheel walking in the simulator, the joint bending 1.3 rad in 3 s and pitching the centre
// unit 0.10 rad, read σ from −0.06 to +0.11 rad, beyond the slant dead band (0.05), and the slant
// response (6.4) pushed the held rear joint out from 1.21 to 1.27–1.50 rad. Filtered alike,
// the pitch and its correction cancel at every instant on flat ground (for small angles acos(g1)
// − π/2 is the filtered pitch), and σ is the filtered slope: ā⁰ and c⁰ = 0 both start from flat
// ground.
//
// Sign convention: nose up by θ on a slope tilts x1 upward, so gravity gains a component
// against x1: a = 9.81 (−sin θ, 0, −cos θ), g1 = −sin θ < 0, acos(g1) = π/2 + θ and σ = θ > 0
// (with αf = αr). Hence a1 < 0 means nose up, σ > 0 means driving uphill (6.2.2's reading),
// and a1 > 0 nose down, σ < 0.
#pragma once

#include <array>

#include "core/params.hpp"

namespace marsokhod::behaviour {

using Vector3 = std::array<double, 3>;

// The gravity filter: the mean ā of the accelerometer's readings, and its direction g.
class GravityEstimate {
 public:
  // ā⁰ = (0, 0, −gravity_mps2): the rover starts assuming flat ground. Throws
  // std::invalid_argument unless gravity_mps2 > 0 and finite.
  explicit GravityEstimate(double gravity_mps2);

  // One step: ā^k = λ ā^(k−1) + (1 − λ) a^k, λ in [0, 1) (0: no filtering). If ā^k vanishes
  // (only possible for λ ≤ 1/2 and a^k exactly against ā^(k−1)) the reading is taken. Throws
  // std::invalid_argument if a^k is not finite or the zero vector (no direction to learn from: a
  // sensor fault, or free fall), or λ is outside [0, 1); the estimate is unchanged then.
  void update(const Vector3& acceleration_mps2, double lambda);

  // g = ā/‖ā‖, a unit vector.
  Vector3 direction() const;
  const Vector3& mean_acceleration_mps2() const { return mean_mps2_; }

 private:
  Vector3 mean_mps2_;
};

// The unit vector g that GravityEstimate starts from: flat ground.
inline constexpr Vector3 kInitialGravityDirection{0.0, 0.0, -1.0};

// σ [rad] from a unit gravity direction g and the lever inclinations αf, αr [rad]. g1 is
// clamped into [−1, 1] against rounding. Throws std::invalid_argument if an input is not
// finite.
double terrain_slope_rad(const Vector3& gravity_direction, double front_lever_inclination_rad,
                         double rear_lever_inclination_rad);

// The slope σ as the driver reads it: the gravity filter and the lever correction
// c = (αr − αf)/2 filtered alike (above),
//   c^k = λ c^(k−1) + (1 − λ)(αr − αf)/2,   c⁰ = 0,   σ = acos(g1) − π/2 + c.
class SlopeEstimate {
 public:
  // Throws std::invalid_argument unless gravity_mps2 > 0 and finite.
  explicit SlopeEstimate(double gravity_mps2);

  // One step of both filters. Throws std::invalid_argument as GravityEstimate::update, or if an
  // inclination is not finite; the estimate is unchanged then.
  void update(const Vector3& acceleration_mps2, double front_lever_inclination_rad,
              double rear_lever_inclination_rad, double lambda);

  double slope_rad() const;
  const GravityEstimate& gravity() const { return gravity_; }
  double lever_correction_rad() const { return correction_rad_; }

 private:
  GravityEstimate gravity_;
  double correction_rad_ = 0.0;
};

// 6.2.1's dead band: σ within it (|σ| < slant_deadband_rad) counts as flat, 0; beyond it σ as it
// is. The slant response (6.4), the slope hold and rolking's slope placement all read σ so.
double slope_beyond_dead_band(double slope_rad, const BehaviourParams& params);

// The uphill side of that σ: +1 when forward is uphill, −1 when backward is, 0 on flat ground.
double uphill_side(double slope_rad, const BehaviourParams& params);

}  // namespace marsokhod::behaviour
