// Sines and cosines of evenly spaced angles θ0, θ0 + δ, θ0 + 2δ, … by rotation: one sincos for
// the start and one for the step, then four multiplications per angle,
//   cos(θ + δ) = cos θ cos δ − sin θ sin δ,   sin(θ + δ) = sin θ cos δ + cos θ sin δ.
// Over the few dozen steps of a contact arc the rounding grows by about one unit in the last place
// per step (≈ 1e-15 after 24), far below anything the soil model resolves; the sequence depends
// only on θ0 and δ, so it is as repeatable as std::sin and std::cos themselves.
#pragma once

#include <cmath>

namespace marsokhod::sim::soil {

class AngleSteps {
 public:
  AngleSteps(double start_rad, double step_rad)
      : cos_(std::cos(start_rad)),
        sin_(std::sin(start_rad)),
        cos_step_(std::cos(step_rad)),
        sin_step_(std::sin(step_rad)) {}

  // θ0 = δ: the multiples δ, 2δ, 3δ, … from one sincos.
  static AngleSteps multiples(double step_rad) {
    const double c = std::cos(step_rad), s = std::sin(step_rad);
    return AngleSteps(c, s, c, s);
  }

  double cos() const { return cos_; }
  double sin() const { return sin_; }
  void advance() {
    const double c = cos_ * cos_step_ - sin_ * sin_step_;
    sin_ = sin_ * cos_step_ + cos_ * sin_step_;
    cos_ = c;
  }

 private:
  AngleSteps(double cos_start, double sin_start, double cos_step, double sin_step)
      : cos_(cos_start), sin_(sin_start), cos_step_(cos_step), sin_step_(sin_step) {}

  double cos_, sin_, cos_step_, sin_step_;
};

}  // namespace marsokhod::sim::soil
