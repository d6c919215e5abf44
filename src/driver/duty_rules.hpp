// Chapter 3.2's rules for the duty cycles the driver sends, and their encoding into 0xi0.
//
// - "Two consecutive requests should not differ significantly in pwm": |d^k − d^(k−1)| ≤ step.
// - "The bit drv should only toggle when pwm is close or equal to zero": the request that toggles
//   drv has |d| ≤ direction_change_duty (and d = 0 is sent with drv = 0).
// - eim = 1 iff pwm/icr < 0.6 (the LS7184 clock converter).
// Together they guarantee that the motors never see a jump in duty cycle, whatever the control
// laws above ask for.
#pragma once

#include <cstdint>

#include "core/params.hpp"
#include "core/protocol/messages.hpp"

namespace marsokhod::driver {

// The duty cycle to send this cycle given the last one sent and the one the control asks for:
// moved toward `wanted` by at most max_duty_step; a cycle that changes drv (the sign) sends at
// most |d| = direction_change_duty. NaN `wanted` keeps the previous duty.
double next_duty(double previous, double wanted, const SafetyParams& safety);

// Encodes d ∈ [−1, 1] (clamped) for µ`node` with the configured icr:
// drv = (d < 0), pwm = round(|d|·icr), eim by the 0.6 rule.
protocol::ControlRequest control_request(std::uint8_t node, double duty, int icr);

// d = (−1)^drv·pwm/icr of a request (for status and tests).
double duty_of(const protocol::ControlRequest& request, int icr);

// The duty µi applies when sent d: duty_of(control_request(·, d, icr), icr), pwm rounded.
double sent_duty(double duty, int icr);

}  // namespace marsokhod::driver
