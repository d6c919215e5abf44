// Chapter 3.3, (3.4): the gyro's null-rate reading y, tracked while the rover stands still.
//
// The ADIS16100 drifts with temperature within about 5 LSB at up to 0.01 LSB/s. While the rover is
// not in motion its true yaw rate is zero, so the reading itself is the null rate and
//   y^(k+1) = λ·y^k + (1 − λ)·yaw^k     (rover still)
//   y^(k+1) = y^k                       (moving: a real turn must not be learnt as bias)
// with y⁰ = the TYP base line 505 and λ close to 1 (filters.gyro_null_lambda). A unit's null
// lies up to 5 counts off the TYP line, and λ = 0.99 forgets y⁰ with a time constant of 1.6 s: a
// rover that stands for the first 2.5 s and then drives kept a fifth of that offset, 0.02 rad/s,
// which turned the dead-reckoned heading (core/estimation) by 0.65 rad in 25 s. So the filter
// starts as a mean: the n-th still reading gets the weight max(1 − λ, 1/(n + 1)), y⁰ counting
// as the first sample — y is the mean of y⁰ and the still readings until 1/(n + 1) falls to 1 − λ
// (100 readings, 1.6 s), then (3.4) as printed. λ = 1 never moves, λ = 0 follows the reading.
#pragma once

namespace marsokhod::tracking {

class GyroNullFilter {
 public:
  // Throws std::invalid_argument unless initial_counts is finite and lambda ∈ [0, 1].
  GyroNullFilter(double initial_counts, double lambda);

  // Feeds yaw^k; returns y^(k+1). rover_still is the driver's judgement that nothing moves.
  // Throws std::invalid_argument if yaw_counts is not finite; the state is unchanged then.
  double update(double yaw_counts, bool rover_still);

  double null_counts() const { return null_counts_; }
  double lambda() const { return lambda_; }

 private:
  double null_counts_;
  double lambda_;
  double still_samples_ = 1.0;  // y⁰ and the still readings so far
};

}  // namespace marsokhod::tracking
