// Chapter 3.2: the eim bit of a control request (0xi0), "update stp on measured direction change".
//
// "Due to the characteristics of the clock converter LS7184" (the thesis says no more), the driver
// lets the controller refresh stp on a direction change only at moderate duty cycles:
//   eim = 1  iff  pwm/icr < 0.6
// With eim = 0 stp is not refreshed; see motor_position.hpp for how a stale stp is handled.
#pragma once

#include <cstdint>

namespace marsokhod::tracking {

inline constexpr double kEncoderInterruptDutyLimit = 0.6;  // pwm/icr below this ⇒ eim = 1

// eim for the duty pwm/icr. Compared in integers (5·pwm < 3·icr), so the boundary is exact.
// Throws std::invalid_argument if icr ≤ 0.
bool direction_change_update_enabled(std::uint16_t pwm, int icr);

}  // namespace marsokhod::tracking
