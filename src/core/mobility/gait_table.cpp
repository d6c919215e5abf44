#include "core/mobility/gait_table.hpp"

#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/checks/checks.hpp"

namespace marsokhod::mobility {
namespace {

using Stroke = JointStroke;
constexpr Stroke kC = Stroke::kContracted;
constexpr Stroke kE = Stroke::kExtended;
constexpr Stroke kM = Stroke::kMidStroke;
constexpr Stroke kH = Stroke::kHeld;

constexpr AxleRule fixed(double front, double rear) {
  return {AxleRule::Kind::kFixed, {front, rear}, 0.5};
}
constexpr AxleRule epsilon_formula(double epsilon) {
  return {AxleRule::Kind::kEpsilonFormula, {}, epsilon};
}

constexpr std::array<GaitState, 2> kRolking{{
    {kC, kE, epsilon_formula(0.5)},  // exterior axles stay, the center advances
    {kE, kC, fixed(1.0, 1.0)},       // exterior axles advance, the center stays
}};
constexpr std::array<GaitState, 2> kFrontWheelWalking{{
    {kC, kH, fixed(0.0, 0.0)},  // front axle stays, center and rear are pulled forward
    {kE, kH, fixed(1.0, 0.0)},  // front axle steps forward
}};
constexpr std::array<GaitState, 2> kRearWheelWalking{{
    {kH, kC, fixed(0.0, 1.0)},  // rear axle steps forward
    {kH, kE, fixed(0.0, 0.0)},  // rear axle stays, center and front are pushed forward
}};
constexpr std::array<GaitState, 2> kWormLike{{
    {kC, kC, fixed(0.0, 1.0)},  // front stays, the rear is pulled in
    {kE, kE, fixed(1.0, 0.0)},  // rear stays, the front is pushed out
}};
constexpr std::array<GaitState, 2> kRolkingExtendedBase{{
    {kM, kE, epsilon_formula(0.5)},
    {kE, kM, fixed(1.0, 1.0)},
}};

[[noreturn]] void reject(std::string_view problem) {
  throw std::invalid_argument("GaitParams: " + std::string(problem) +
                              "; fix [gaits] in config/marsokhod.toml");
}

StrokePositions stroke_positions(double sign, const JointBounds& bounds,
                                 const GeometryParams& geometry, const GaitParams& gait) {
  validate(gait, geometry);
  const double contracted = contracted_bending_rad(geometry);
  return {bounds.clamp(sign * contracted), bounds.clamp(sign * gait.extended_rad),
          bounds.clamp(sign * 0.5 * (contracted + gait.extended_rad))};
}

}  // namespace

std::string_view gait_name(Gait gait) {
  switch (gait) {
    case Gait::kNone: return "none";
    case Gait::kRolking: return "rolking";
    case Gait::kFrontWheelWalking: return "front-wheel walking";
    case Gait::kRearWheelWalking: return "rear-wheel walking";
    case Gait::kWormLike: return "worm-like";
    case Gait::kRolkingExtendedBase: return "rolking with extended base";
  }
  return "unknown";
}

namespace {

constexpr std::array<std::pair<Gait, std::string_view>, 6> kGaitIds = {{
    {Gait::kNone, "none"},
    {Gait::kRolking, "rolking"},
    {Gait::kFrontWheelWalking, "front-wheel-walking"},
    {Gait::kRearWheelWalking, "rear-wheel-walking"},
    {Gait::kWormLike, "worm-like"},
    {Gait::kRolkingExtendedBase, "rolking-extended-base"},
}};

}  // namespace

std::string_view gait_id(Gait gait) {
  for (const auto& [value, id] : kGaitIds) {
    if (value == gait) return id;
  }
  return "none";
}

std::optional<Gait> gait_from_id(std::string_view id) {
  for (const auto& [gait, name] : kGaitIds) {
    if (id == name) return gait;
  }
  return std::nullopt;
}

std::span<const GaitState> gait_states(Gait gait) {
  switch (gait) {
    case Gait::kNone: return {};
    case Gait::kRolking: return kRolking;
    case Gait::kFrontWheelWalking: return kFrontWheelWalking;
    case Gait::kRearWheelWalking: return kRearWheelWalking;
    case Gait::kWormLike: return kWormLike;
    case Gait::kRolkingExtendedBase: return kRolkingExtendedBase;
  }
  return {};
}

GaitState mirrored(const GaitState& state) {
  GaitState result{state.rear, state.front, state.rule};
  result.rule.fixed = {state.rule.fixed.rear, state.rule.fixed.front};
  result.rule.epsilon = 1.0 - state.rule.epsilon;
  return result;
}

GaitState gait_state(Gait gait, std::size_t index, DrivingIntent intent) {
  const std::span<const GaitState> states = gait_states(gait);
  if (index >= states.size()) {
    std::ostringstream message;
    message << "gait_state: " << gait_name(gait) << " has " << states.size() << " states, no state "
            << index;
    throw std::out_of_range(message.str());
  }
  return intent == DrivingIntent::kBackward ? mirrored(states[index]) : states[index];
}

void validate(const GaitParams& gait, const GeometryParams& geometry) {
  checks::law::require_finite(gait.extended_rad, "GaitParams", "extended_rad (E, 2.55)");
  checks::law::require_finite(gait.max_joint_speed_fraction, "GaitParams",
                          "max_joint_speed_fraction (0.5)");
  if (!(gait.extended_rad > contracted_bending_rad(geometry))) {
    reject("extended_rad must exceed acos(a/b) = " +
           std::to_string(contracted_bending_rad(geometry)) + " (the contracted stroke)");
  }
  if (!(gait.max_joint_speed_fraction > 0.0 && gait.max_joint_speed_fraction <= 1.0)) {
    reject("max_joint_speed_fraction must lie in (0, 1] (a fraction of w)");
  }
}

StrokePositions front_stroke_positions(const GeometryParams& geometry, const GaitParams& gait,
                                       const JointParams& joints) {
  return stroke_positions(-1.0, front_joint_bounds(joints), geometry, gait);
}

StrokePositions rear_stroke_positions(const GeometryParams& geometry, const GaitParams& gait,
                                      const JointParams& joints) {
  return stroke_positions(1.0, rear_joint_bounds(joints), geometry, gait);
}

double stroke_target_rad(JointStroke stroke, const StrokePositions& positions,
                         double held_position_rad) {
  switch (stroke) {
    case JointStroke::kContracted: return positions.contracted_rad;
    case JointStroke::kExtended: return positions.extended_rad;
    case JointStroke::kMidStroke: return positions.mid_stroke_rad;
    case JointStroke::kHeld: break;
  }
  checks::law::require_finite(held_position_rad, "stroke_target_rad", "held_position_rad");
  return held_position_rad;
}

}  // namespace marsokhod::mobility
