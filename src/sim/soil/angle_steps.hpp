// Sines and cosines of evenly spaced angles θ0, θ0 + δ, θ0 + 2δ, … by rotation: one sincos for
// the start and one for the step, then four multiplications per angle,
//   cos(θ + δ) = cos θ cos δ − sin θ sin δ,   sin(θ + δ) = sin θ cos δ + cos θ sin δ.
// Over the few dozen steps of a contact arc the rounding grows by about one unit in the last place
// per step (≈ 1e-15 after 24), far below anything the soil model resolves; the sequence depends
// only on θ0 and δ, so it is as repeatable as plain arithmetic. The first sines and cosines come
// from sin_cos (fast_math.hpp).
#pragma once

#include "sim/soil/fast_math.hpp"

namespace marsokhod::sim::soil {

class AngleSteps {
 public:
  AngleSteps(double start_rad, double step_rad)
      : AngleSteps(sin_cos(start_rad), sin_cos(step_rad)) {}

  // θ0 = δ: the multiples δ, 2δ, 3δ, … from one sincos.
  static AngleSteps multiples(double step_rad) {
    const SinCos step = sin_cos(step_rad);
    return AngleSteps(step, step);
  }

  double cos() const { return cos_; }
  double sin() const { return sin_; }
  void advance() {
    const double c = cos_ * cos_step_ - sin_ * sin_step_;
    sin_ = sin_ * cos_step_ + cos_ * sin_step_;
    cos_ = c;
  }

 private:
  AngleSteps(SinCos start, SinCos step)
      : cos_(start.cos), sin_(start.sin), cos_step_(step.cos), sin_step_(step.sin) {}

  double cos_, sin_, cos_step_, sin_step_;
};

}  // namespace marsokhod::sim::soil
