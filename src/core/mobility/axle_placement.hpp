// Where the axles go while the joints bend: the driving intent ϱ and the ρ table of Remark 5.5,
// and the exterior-axle placement for two bending joints (chapter 5.3, docs/design.md).
//
// Remark 5.5:  ϱ^(k+1) = 0 if v1ᵈ > 0 (forward), 1 if v1ᵈ < 0 (backward), ϱ^k if v1ᵈ = 0; ϱ⁰ = 0.
//   intention        ρf      ρr
//   increase c       1 − ϱ   ϱ        (the axle that moves is the one ahead in the driving
//   decrease c       ϱ       1 − ϱ     direction: walking forward moves the front out first)
//
// Two joints at once. With y the axle-distance rate a joint causes, in the joints' motor sign
//   yf = (ab·sin γf/cf)·w6 = −∂t cf,   yr = (ab·sin γr/cr)·w7 = +∂t cr      [m/s]
// (yf > 0 while the front joint contracts, yr > 0 while the rear joint extends), the rows of
// n6·w6 + n7·w7 (5.1)/(5.2) roll the exterior axles forward at
//   af = yr − q   (front),   ar = yf − q   (rear),   q = ρf·yf + ρr·yr          [m/s]
// and the center axle at yf + yr − q. af² + ar² is least on the line q = (yf + yr)/2; the point
// of that line nearest to (ε, 1 − ε) is
//   ρf = (yf² + (2ε − 1)·yf·yr + 2ε·yr²) / (2(yf² + yr²))
//   ρr = (2(1 − ε)·yf² + (1 − 2ε)·yf·yr + yr²) / (2(yf² + yr²))
// as printed in chapter 5.3. yf = yr = 0 gives (ε, 1 − ε). The wheel velocities depend on ρf, ρr
// only through q, so ε only picks the representative: the motion is the same for every ε. The
// result may leave [0, 1] when one joint is much faster than the other (yf = 1, yr = 3, ε = 0
// gives ρf = −0.1); (5.1)/(5.2) are linear in ρ and stay valid. Compute it every cycle from the
// measured joint velocities, so unsynchronised joints (backlash) still keep the axles in place.
#pragma once

#include "core/params.hpp"

namespace marsokhod::mobility {

// ϱ of Remark 5.5.
enum class DrivingIntent { kForward = 0, kBackward = 1 };

// ϱ^(k+1) from ϱ^k and the target velocity v1ᵈ [rad/s]; throws on a non-finite v1ᵈ.
DrivingIntent driving_intent(DrivingIntent previous, double drive_target_radps);

// ϱ as the number 0 or 1.
double intent_value(DrivingIntent intent);

// Whether the operator or a gait wants the axle distance c to grow or to shrink.
enum class ClearanceIntent { kIncrease, kDecrease };

// The exterior-axle factors ρf of (5.1) and ρr of (5.2).
struct AxleFactors {
  double front = 0.0;  // ρf
  double rear = 0.0;   // ρr
};

// Remark 5.5's table for each joint's own intention.
double front_axle_factor(DrivingIntent intent, ClearanceIntent front_clearance);
double rear_axle_factor(DrivingIntent intent, ClearanceIntent rear_clearance);

// The joint velocity's intention: a front joint extends (c grows) for w6 < 0, a rear joint for
// w7 > 0 (p6 = −γf, p7 = +γr; c grows with γ on (5.3)). A still joint counts as decrease: its
// n·w vanishes anyway.
ClearanceIntent front_clearance_intent(double front_joint_velocity_radps);
ClearanceIntent rear_clearance_intent(double rear_joint_velocity_radps);

// yf, yr above [m/s].
struct AxleDistanceRates {
  double front_mps = 0.0;  // yf
  double rear_mps = 0.0;   // yr
};
AxleDistanceRates axle_distance_rates(double front_joint_position_rad,
                                      double rear_joint_position_rad,
                                      double front_joint_velocity_radps,
                                      double rear_joint_velocity_radps,
                                      const GeometryParams& geometry);

// The printed ρf, ρr for the rates and ε ∈ [0, 1] (the desired ρf).
AxleFactors two_joint_axle_factors(const AxleDistanceRates& rates, double epsilon);

// On a slope (our extension, docs/decisions.md "Rolking's placement on a slope"): the joints'
// mismatch goes uphill. The printed formula's q = (yf + yr)/2 splits a mismatch yf ≠ yr evenly,
// af = (yr − yf)/2 = −ar: one anchor is asked downhill. On soft sand an anchor asked downhill
// rolls down with the slope's pull and gives up the soil it had sheared, and the other, asked
// uphill, cannot follow: the rover loses ground at every stroke (docs/simulator.md, "Rolking's
// anchors on a slope"). With u = +1 when forward is uphill (σ > 0) and −1 when backward is, q is
// chosen so that neither anchor moves downhill, u·af ≥ 0 and u·ar ≥ 0, and as near the even
// split as that allows:
//   q = min(yf, yr) for u = +1,   q = max(yf, yr) for u = −1,
// so the centre advances at the faster joint's rate (u = +1) and the slower joint's anchor is
// asked uphill by the difference; equal rates give the printed formula's motion. ρ is the point
// of the line ρf·yf + ρr·yr = q inside [0, 1]² nearest to (ε, 1 − ε) (the line always crosses
// the square for these q). Throws std::invalid_argument for non-finite rates, ε outside [0, 1]
// or u not ±1.
AxleFactors uphill_axle_factors(const AxleDistanceRates& rates, double epsilon, double uphill);

// af, ar above [m/s]: the forward velocities of the front and rear exterior axles.
struct ExteriorAxleVelocities {
  double front_mps = 0.0;  // af
  double rear_mps = 0.0;   // ar
};
ExteriorAxleVelocities exterior_axle_velocities(const AxleDistanceRates& rates,
                                                const AxleFactors& factors);

}  // namespace marsokhod::mobility
