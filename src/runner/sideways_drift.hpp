// The sideways drift of the centre unit: how far it moved along its left axis over the last
// second, per second. Field Experiment 5.2 asks whether m3 "propels Marsokhod sideways"; on soft
// soil the chassis also shakes sideways by a few cm/s for tens of milliseconds while the wheels'
// shear states load and let go (docs/simulator.md), moving it by tenths of a millimetre. The
// instantaneous sideways speed (max_lateral_speed_mps) sees that shaking; the drift over a
// second sees only what carries the rover away.
//
// drift(t) = |(p(t) − p(t₀))·l(t)| / (t − t₀), t₀ the latest sample at or before t − window, l(t)
// the centre unit's horizontal left axis (−sin ψ, cos ψ) at t. None until a whole window lies
// behind the first sample.
#pragma once

#include <cmath>
#include <deque>
#include <optional>

namespace marsokhod::runner {

class SidewaysDrift {
 public:
  explicit SidewaysDrift(double window_s = 1.0) : window_s_(window_s) {}

  // One sample: time [s], horizontal position [m], heading ψ [rad]. Samples come in time order.
  std::optional<double> add(double time_s, double x_m, double y_m, double yaw_rad) {
    samples_.push_back({time_s, x_m, y_m});
    const double cut_s = time_s - window_s_ + 1e-9;
    while (samples_.size() >= 2 && samples_[1].time_s <= cut_s) samples_.pop_front();
    const Sample& first = samples_.front();
    if (first.time_s > cut_s) return std::nullopt;
    const double sideways_m =
        -std::sin(yaw_rad) * (x_m - first.x_m) + std::cos(yaw_rad) * (y_m - first.y_m);
    return std::abs(sideways_m) / (time_s - first.time_s);
  }

 private:
  struct Sample {
    double time_s, x_m, y_m;
  };
  double window_s_;
  std::deque<Sample> samples_;
};

}  // namespace marsokhod::runner
