// The wheel-walking gaits of chapter 5.3 as data (docs/design.md "Wheel-walking gaits"; the thesis'
// tables are lost). A gait is a cycle of states; each state names the stroke of the front and the
// rear joint and the rule for ρf, ρr during the transition into it. The next state starts when
// both joints have reached their targets and stopped (gait_sequencer.hpp).
//
// Strokes, in each joint's own coordinate (p6 = −γf, p7 = +γr), clamped into (5.3):
//   C contracted   p6 = −acos(a/b),   p7 = +acos(a/b)         (lever vertical, c = 0.387 m)
//   E extended     p6 = −extended_rad, p7 = +extended_rad      (GaitParams, 2.55: c = 0.539 m)
//   M mid-stroke   midway in angle between C and E             (±1.881 rad)
//   H held         the joint keeps the position it had when the gait started
//
// Tables for driving forward (ϱ = 0), state 0 first; "→ X with ρ" is the transition into X:
//   rolking                 (C,E) with ε = ½  →  (E,C) with ρf = ρr = 1
//   front-wheel walking     (C,H) with ρf = 0 →  (E,H) with ρf = 1
//   rear-wheel walking      (H,C) with ρr = 1 →  (H,E) with ρr = 0
//   worm-like               (C,C) with ρf = 0, ρr = 1  →  (E,E) with ρf = 1, ρr = 0
//   rolking, extended base  (M,E) with ε = ½  →  (E,M) with ρf = ρr = 1
// (C,E) → (E,C) with ρ = (1, 1): the exterior axles advance, the center stays; (E,C) → (C,E) by
// the ε-formula (axle_placement.hpp): the exterior axles stay, the center advances. Any ε gives
// the same wheel velocities; ½ is the one that mirroring leaves unchanged. A held joint gets
// ρ = 0: should it drift, its own exterior axle stays.
//
// Driving backward (ϱ = 1) mirrors front and rear: strokes swap joints, (ρf, ρr) → (ρr, ρf),
// ε → 1 − ε. Mirrored front-wheel walking walks backward on the rear wheels.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string_view>

#include "core/mobility/axle_placement.hpp"
#include "core/mobility/lever_geometry.hpp"
#include "core/params.hpp"

namespace marsokhod::mobility {

enum class Gait {
  kNone,
  kRolking,
  kFrontWheelWalking,
  kRearWheelWalking,
  kWormLike,
  kRolkingExtendedBase,
};

// "none", "rolking", "front-wheel walking", … for logs and the console.
std::string_view gait_name(Gait gait);

// The gaits' ids in the operator protocol, scenario files and recordings: "none", "rolking",
// "front-wheel-walking", "rear-wheel-walking", "worm-like", "rolking-extended-base".
std::string_view gait_id(Gait gait);
std::optional<Gait> gait_from_id(std::string_view id);  // nullopt for an unknown id
// Every gait, kNone first, in the order of the enum.
inline constexpr std::array<Gait, 6> kAllGaits{Gait::kNone,           Gait::kRolking,
                                               Gait::kFrontWheelWalking, Gait::kRearWheelWalking,
                                               Gait::kWormLike,       Gait::kRolkingExtendedBase};

enum class JointStroke { kContracted, kExtended, kMidStroke, kHeld };

// How ρf, ρr are chosen during a transition.
struct AxleRule {
  enum class Kind { kFixed, kEpsilonFormula };
  Kind kind = Kind::kFixed;
  AxleFactors fixed;     // kFixed: these ρf, ρr
  double epsilon = 0.5;  // kEpsilonFormula: two_joint_axle_factors(measured rates, ε)
};

struct GaitState {
  JointStroke front = JointStroke::kHeld;
  JointStroke rear = JointStroke::kHeld;
  AxleRule rule;  // for the transition into this state
};

// The table for ϱ = 0; empty for Gait::kNone.
std::span<const GaitState> gait_states(Gait gait);

// Front and rear swapped (see above).
GaitState mirrored(const GaitState& state);

// State `index` of the gait's table for the driving intent (mirrored when backward). Throws
// std::out_of_range if index ≥ gait_states(gait).size().
GaitState gait_state(Gait gait, std::size_t index, DrivingIntent intent);

// Throws std::invalid_argument unless extended_rad is finite and > acos(a/b), and
// max_joint_speed_fraction lies in (0, 1].
void validate(const GaitParams& gait, const GeometryParams& geometry);

// C, E and M of one joint in its own coordinate, each clamped into (5.3).
struct StrokePositions {
  double contracted_rad = 0.0;
  double extended_rad = 0.0;
  double mid_stroke_rad = 0.0;
};
StrokePositions front_stroke_positions(const GeometryParams& geometry, const GaitParams& gait,
                                       const JointParams& joints);
StrokePositions rear_stroke_positions(const GeometryParams& geometry, const GaitParams& gait,
                                      const JointParams& joints);

// The target for one joint: its stroke position, or held_position_rad for kHeld.
double stroke_target_rad(JointStroke stroke, const StrokePositions& positions,
                         double held_position_rad);

}  // namespace marsokhod::mobility
