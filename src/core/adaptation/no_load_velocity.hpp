// (4.3) the no-load velocity ŵ of a calibrated wheel or joint and the duty cycle that yields it:
//   ŵ = ζ · W_icr(d) · U/Ū        d = W_icr⁻¹(ŵ/ζ · Ū/U)
// ζ is the motor's scale factor (Procedure 4.5, MotorParams::scale), U the measured supply
// voltage, Ū the nominal supply of the calibration (24 V). The duty saturates to ±1 when ŵ
// asks for more than the motor gives at U (see MotorCurve).
#pragma once

#include "core/adaptation/motor_curve.hpp"

namespace marsokhod::adaptation {

// ŵ in rad/s. Throws std::invalid_argument if duty is not finite, or zeta, supply_v or
// nominal_supply_v is not finite and positive, or if the product overflows; |duty| > 1
// saturates.
double no_load_velocity(const MotorCurve& curve, double duty, double zeta, double supply_v,
                        double nominal_supply_v);

// d in [−1, 1] for a no-load velocity of w_hat_radps. Same checks, w_hat_radps finite.
double duty_for_no_load_velocity(const MotorCurve& curve, double w_hat_radps, double zeta,
                                 double supply_v, double nominal_supply_v);

// Remark 4.7, passive control: d_i^(k+1) = W⁻¹(w_i^k/ζ_i · Ū/U^k), the duty at which wheel i
// runs freely at the velocity it was measured at, so it picks up the ambient speed instead of
// resisting it (loads → 0, Remark 4.12). A wheel measured faster than the motor can turn at U
// gets ±1; limiting the step between consecutive duties is the caller's job (chapter 3.2).
double passive_duty(const MotorCurve& curve, double measured_velocity_radps, double zeta,
                    double supply_v, double nominal_supply_v);

}  // namespace marsokhod::adaptation
