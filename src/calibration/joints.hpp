// Procedure 4.3 (initialisation) with Procedure 4.1 (the joints' backlash b6, b7).
//
// Procedure 4.1 straps the rover to the ground "so that neither the wheels rotate nor the joints
// incline" and turns the joint motors at small duty cycles d = ±0.1: with the joint held, the
// shaft crosses the gap [p, p + b] and stops at its far end, so the travel between the resting
// positions after two opposite holds is b. Several reversals give b's mean and spread; a shaft
// that does not come to rest means the joint moved (not strapped) and the hold is refused.
//
// Procedure 4.3 then is the driver's own start-up step (driver/startup.hpp, also the console's
// calibration mode): d6 = d7 = −0.08 until the shafts rest at the negative end of their gaps
// (≤ 3 s), after which p⁰ := p̄⁰ = ∓1.2121 (Remark 3.1). The bench runs that very code.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "calibration/bench.hpp"
#include "calibration/procedure.hpp"
#include "core/params.hpp"

namespace marsokhod::calibration {

// The end of one hold at a constant duty cycle.
struct JointHold {
  double duty = 0.0;             // the sign is the direction
  double rest_shaft_rad = 0.0;   // p̄ averaged over the hold's last quarter second
  double rest_speed_radps = 0.0; // |w̄| averaged over the same: ≈ 0 when the shaft rests
};

// What the Procedure 4.3 run of driver::Startup did.
struct JointInitialisation {
  double duration_s = 0.0;
  std::array<double, 2> travel_rad{};  // p̄ moved toward the negative end (front, rear)
  bool timed_out = false;              // it took the full 3 s
  // How far each shaft dragged its joint after they met (driver::Startup::over_travel_rad): the
  // joints stand there below Remark 3.1's p⁰.
  std::array<double, 2> dragged_rad{};
};

struct JointLimits {
  std::size_t min_travels = 3;           // per joint: reversals measured
  double max_rest_speed_radps = 0.01;    // a shaft slower than this rests on the gap's end
  // The travels of one joint agree within this spread (σ): fraction of the mean plus a floor
  // for the encoder and the gap ends' give.
  double max_spread_fraction = 0.1;
  double max_spread_floor_rad = 0.003;
  // A plausible play: not none (the joint moved with the shaft), not a free-wheeling shaft.
  double min_backlash_rad = 0.005;
  double max_backlash_rad = 0.6;
};

// b6, b7 from the holds of each joint (holds[0]: front, holds[1]: rear, in order); the wheels'
// entries of `configured`'s backlash vector are kept.
ProcedureResult fit_joints(const std::array<std::vector<JointHold>, 2>& holds,
                           const JointInitialisation& initialisation,
                           const MotorParams& configured, const JointLimits& limits = {});

// Procedure 4.3 on the bench with driver::Startup's calibration step (the driver's start-up and
// the console's calibration mode run the same code).
JointInitialisation initialise_joints(Bench& bench);

// Moves the joints to p6, p7 (the joints themselves, (4.1): p = P(p̄, p, b) with the configured
// backlash) by a small closed loop on the shafts; the wheels stand still (on the stand they turn
// freely). Starts from the state Procedure 4.3 leaves: the joints in vertical configuration, the
// shafts at the negative end of their gaps, p = p̄ = ∓1.2121 less what the start-up dragged them
// (`dragged_rad`, JointInitialisation's; the bench's p̄ is offset to that).
class JointMover {
 public:
  explicit JointMover(const Bench& bench, std::array<double, 2> dragged_rad = {});
  // Returns true when both joints are within tolerance_rad of their targets (then at rest),
  // false after timeout_s.
  bool move_to(Bench& bench, double front_rad, double rear_rad, double tolerance_rad = 0.015,
               double timeout_s = 15.0);
  // p6, p7 by (4.1), updated from the bench's latest p̄.
  std::array<double, 2> joint_rad() const { return joint_rad_; }

 private:
  void track(const BenchSample& sample);

  std::array<double, 2> backlash_rad_{};
  std::array<double, 2> joint_rad_{};
  std::array<double, 2> shaft_offset_rad_{};  // Procedure 4.3's p̄⁰ minus the bench's p̄ then
};

}  // namespace marsokhod::calibration
