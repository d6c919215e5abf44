// The joint bounds the driver steers by: (5.3) less what the driver cannot know of a unit's
// backlash gap.
//
// The driver sees the joints only through their motors' shafts p̄ and the backlash model
// (4.1)/(4.2) with the configured gap b. Procedure 4.3 (startup.hpp) ends with each shaft
// resting on the negative end of its gap, engaged with its joint, and sets p = p̄ there. From
// then on:
// - pushing a joint in the negative direction, the shaft drags it at the gap's negative end:
//   the joint is the shaft, p = p̄, whatever the unit's true gap b_t;
// - pushing it in the positive direction, the shaft drags it at the positive end: the joint is
//   p̄ − b_t, the driver's p = p̄ − b. The true joint lies b − b_t above the driver's p.
// A unit's gap differs from the configured one by up to `backlash_uncertainty`·b (a drawn unit
// of the simulator: 6–15 %; a real rover: what Procedure 4.1 left uncertain), so a joint driven
// to its positive bound may pass it by up to that much. The driver therefore keeps its own
// estimate that far inside the positive bounds — but only as far as the shaft has crossed its gap
// toward the positive end: the margin is backlash_uncertainty·b·P⁺(p̄, p, b) of (4.2) (0 with
// the shaft at the negative end, where the estimate is exact, as after Procedure 4.3; the full
// 0.0078 and 0.0375 rad with the thesis' 3° and 14° gaps while the shaft pushes the joint). A
// joint resting at its positive bound after Procedure 4.3 (p6 = −1.2121) is thus not moved.
// The negative bounds need no margin. Targets near a positive bound (the gaits' strokes) are
// planned inside the full margin (joint_bounds_with_backlash_margin), where the joint ends up
// after a positive push.
#pragma once

#include "core/params.hpp"

namespace marsokhod::driver {

// (5.3) with the positive bounds moved in by the full margin. Throws std::invalid_argument when
// the margin leaves a joint no range (max ≤ min).
JointParams joint_bounds_with_backlash_margin(const JointParams& joints, const MotorParams& motors);

// The margin [rad] for one joint now: uncertainty·b·P⁺(p̄, p, b).
double positive_bound_margin_rad(double backlash_uncertainty, double backlash_rad,
                                 double shaft_position_rad, double joint_position_rad);

}  // namespace marsokhod::driver
