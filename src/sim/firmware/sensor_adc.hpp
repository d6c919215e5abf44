// µ8's analog inputs: the true state → 10-bit readings, the thesis' conversions of chapter 3.3
// run backwards with the simulator's true constants (SensorTruth), before noise and quantisation.
//
//   yaw  = y(t) − ω3/0.0170                              inverse of (3.4)
//   acc_i = (acc_i(g) + acc_i(−g))/2 − a_i·(acc_i(g) − acc_i(−g))/(2g)   inverse of (3.5)
//   tlt  = (θ_pot − offset)/gain                         inverse of Procedure 3.4
//   vcc  = (U − offset)/gain                             inverse of Procedure 3.5
// with the gyro's null rate y(t) = base + A·sin(2πt/P + φ) (drift within a 5 LSB window at no
// more than 0.01 LSB/s) and θ_pot the potentiometer shaft behind its backlash.
// Checked against the TYP column: flat ground, at rest, 24.57 V gives yaw 505, acc 279/251.5/376,
// vcc 970.
#pragma once

#include <cstdint>

#include "core/params.hpp"
#include "sim/electrics/sim_truth.hpp"

namespace marsokhod::sim {

inline constexpr std::uint16_t kAdcMaxCounts = 1023;

// y(t) [counts].
double gyro_null_counts(const SensorTruth& truth, double time_s);
double gyro_counts(double yaw_rate_radps, double null_counts, double radps_per_count);
double accelerometer_counts(double accel_mps2, const AccelerometerAxisParams& axis,
                            double gravity_mps2);
// Inverse of physical = gain·counts + offset (tilt and supply).
double conversion_counts(double physical, const LinearConversion& conversion);

// Rounds to the nearest count and clamps to the ADC's 0..1023.
std::uint16_t quantise_adc(double counts);

// A potentiometer shaft driven through play of width backlash_rad: it stays put while the axle's
// tilt θ moves inside [θ_pot − b/2, θ_pot + b/2] and is dragged along at the edges, so after a
// reversal θ must travel the whole play b before the reading moves again; the reading is off by
// at most b/2 (±4° with the 8° of play).
class PotentiometerBacklash {
 public:
  PotentiometerBacklash(double backlash_rad, double initial_tilt_rad)
      : half_play_rad_(backlash_rad / 2.0), shaft_rad_(initial_tilt_rad) {}

  // Feeds the axle's tilt; returns the shaft angle the potentiometer reads.
  double update(double tilt_rad);
  double shaft_rad() const { return shaft_rad_; }

 private:
  double half_play_rad_;
  double shaft_rad_;
};

}  // namespace marsokhod::sim
