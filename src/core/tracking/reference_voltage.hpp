// Procedure 3.5: the reference supply voltage Ū, the battery's voltage with the motors stopped.
//
//   Ū^(k+1) = max(Ũ^k, λ·Ū^k + (1 − λ)·U^k)   if d_i^k = 0 for all motors i = 0..7
//   Ū^(k+1) = max(Ũ^k, Ū^k)                   otherwise
//   Ū^(k+1) = Ũ^k                             for the first N = 16 readings (k < N)
// While the motors are driven, U drops under load and Ū holds (it can only rise, if U rises
// above it); with all duty cycles zero Ū relaxes toward U, tracking the battery discharge.
//
// Two departures from the thesis, both for the same reason. Ũ^k is the mean of the last
// N = kSupplyAveragingReadings readings, where the thesis takes the maximum with the raw reading
// U^k (to ensure U ≤ Ū), and the thesis starts from Ū⁰ = U⁰, one raw reading. µ8's 10-bit
// reading is noisy (quantisation ±34 mV and a few tenths of a count of noise), and a maximum
// over noisy readings ratchets up: one reading a count high (0.068 V) lifts Ū at once, and Ū
// holds it for as long as the motors run, so the drop Ū − U of (4.5), which Figure 6.1 holds
// under Υ, reads a count too high for the whole drive. In the simulator a first reading a count
// high set Ū⁰ = 25.514 V over a rest voltage read as 25.447 V, held through Procedure 4.3's
// joint motion into the drive. The mean of 16 readings (0.25 s) has a quarter of the noise and
// no bias: Ū estimates the rest voltage. Ũ ≤ Ū holds every cycle; a single reading may lie
// above Ū by its noise (a drop of −1 count at rest).
#pragma once

#include <array>
#include <cstddef>

namespace marsokhod::tracking {

inline constexpr std::size_t kSupplyAveragingReadings = 16;

class ReferenceVoltage {
 public:
  // Throws std::invalid_argument unless lambda ∈ [0, 1] (filters.reference_voltage_lambda).
  explicit ReferenceVoltage(double lambda);

  // Feeds U^k [V]; returns Ū^(k+1) [V]. The first call returns Ū¹ = U⁰.
  // Throws std::invalid_argument if supply_v is not finite; the state is unchanged then.
  double update(double supply_v, bool all_duty_zero);

  bool started() const { return started_; }
  double reference_v() const { return reference_v_; }
  // Ũ: the mean of the last kSupplyAveragingReadings readings (of all so far, before that many).
  double mean_supply_v() const;

 private:
  double lambda_;
  double reference_v_ = 0.0;
  bool started_ = false;
  std::array<double, kSupplyAveragingReadings> readings_v_{};
  std::size_t reading_count_ = 0;  // readings seen, capped at kSupplyAveragingReadings
  std::size_t next_reading_ = 0;   // where the next reading goes in the ring
};

}  // namespace marsokhod::tracking
