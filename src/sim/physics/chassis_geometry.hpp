// The side view of one lever (Figure 3.3, chapter 5's table): the center axle, the joint at the
// end of a strut of length b, the exterior axle at the end of the lever of length a. γ is the
// angle at the joint between the strut and the lever (γf = −p6, γr = +p7):
//   c(γ) = sqrt(a² + b² − 2ab·cos γ)                 clearance of the exterior to the center axle
//   α(γ) = arccos((b² + c² − a²) / (2bc))             elevation of the strut above the axles' line
// With the joints vertical, γ = arccos(a/b): the lever hangs straight down, c = sqrt(b² − a²) and
// α = arcsin(a/b), the table's maximum elevation 0.359 rad.
#pragma once

#include "core/params.hpp"

namespace marsokhod::sim {

// Chapter 3.1 table: the clearance c between center and exterior axle spans 0.333–0.550 m, and
// the exterior axles tilt by θ within ±0.524 rad.
inline constexpr double kMinAxleDistanceM = 0.333;
inline constexpr double kMaxAxleDistanceM = 0.550;
inline constexpr double kMaxAxleTiltRad = 0.524;

double axle_distance_m(const GeometryParams& geometry, double bend_rad);
double strut_elevation_rad(const GeometryParams& geometry, double bend_rad);
// The bend γ at which the lever hangs vertically: arccos(a/b) (Remark 3.1: 1.2121 rad).
double vertical_bend_rad(const GeometryParams& geometry);
// γ for a clearance c (the inverse of axle_distance_m), clamped to the reachable [b − a, b + a].
double bend_for_axle_distance_rad(const GeometryParams& geometry, double axle_distance_m);

struct BendRange {
  double min_rad = 0.0;
  double max_rad = 0.0;
};
// The joints' mechanical stops, from the table's clearance range c ∈ [0.333, 0.550] m; wider than
// the driver's bounds (5.3), which keep the joints inside [1.2121, 2.55].
BendRange mechanical_bend_range(const GeometryParams& geometry);

// Throws std::invalid_argument unless 0 < a < b, r > 0 and the track is wider than a wheel.
void validate_geometry(const GeometryParams& geometry);

}  // namespace marsokhod::sim
