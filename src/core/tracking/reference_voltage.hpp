// Procedure 3.5: the reference supply voltage Ū, the battery's voltage with the motors stopped.
//
//   Ū^(k+1) = max(U^k, λ·Ū^k + (1 − λ)·U^k)   if d_i^k = 0 for all motors i = 0..7
//   Ū^(k+1) = max(U^k, Ū^k)                   otherwise
//   Ū⁰ = U⁰
// While the motors are driven, U drops under load and Ū holds (it can only rise, if U rises
// above it); with all duty cycles zero Ū relaxes toward U, tracking the battery discharge. In
// both cases U^k ≤ Ū^(k+1): the drop Ū − U of (4.5) is never negative.
#pragma once

namespace marsokhod::tracking {

class ReferenceVoltage {
 public:
  // Throws std::invalid_argument unless lambda ∈ [0, 1] (filters.reference_voltage_lambda).
  explicit ReferenceVoltage(double lambda);

  // Feeds U^k [V]; returns Ū^(k+1) [V]. The first call sets Ū⁰ = U⁰ and returns Ū¹ = U⁰.
  // Throws std::invalid_argument if supply_v is not finite; the state is unchanged then.
  double update(double supply_v, bool all_duty_zero);

  bool started() const { return started_; }
  double reference_v() const { return reference_v_; }

 private:
  double lambda_;
  double reference_v_ = 0.0;
  bool started_ = false;
};

}  // namespace marsokhod::tracking
