// The sideways drift of the centre unit: how far it moved along its left axis over the last
// second, per second. Field Experiment 5.2 asks whether m3 "propels Marsokhod sideways"; on soft
// soil the chassis also shakes sideways by a few cm/s for tens of milliseconds while the wheels'
// shear states load and let go (docs/simulator.md), moving it by tenths of a millimetre. The
// instantaneous sideways speed (max_lateral_speed_mps) sees that shaking; the drift over a
// second sees only what carries the rover away.
//
// The sideways travel s accumulates each step's displacement along the left axis the rover had
// during it, l = (−sin ψ, cos ψ) at the mean of the step's two headings (the chord of an arc
// points along it), so a rover driving ahead while it turns travels no sideways (a projection
// of the whole window's displacement on the last heading would read v·ω·T/2 of it: 1.8 cm/s at
// 0.1 m/s and 0.36 rad/s). drift(t) = |s(t) − s(t₀)| / (t − t₀), t₀ the
// latest sample at or before t − window; none until a whole window lies behind the first sample.
#pragma once

#include <cmath>
#include <deque>
#include <numbers>
#include <optional>

namespace marsokhod::runner {

class SidewaysDrift {
 public:
  explicit SidewaysDrift(double window_s = 1.0) : window_s_(window_s) {}

  // One sample: time [s], horizontal position [m], heading ψ [rad]. Samples come in time order.
  std::optional<double> add(double time_s, double x_m, double y_m, double yaw_rad) {
    if (!samples_.empty()) {
      // Along the mean of the two samples' left axes: the step's own heading to first order.
      const double yaw = last_yaw_rad_ + 0.5 * std::remainder(yaw_rad - last_yaw_rad_, 2.0 * std::numbers::pi);
      sideways_m_ += -std::sin(yaw) * (x_m - last_x_m_) + std::cos(yaw) * (y_m - last_y_m_);
    }
    last_x_m_ = x_m;
    last_y_m_ = y_m;
    last_yaw_rad_ = yaw_rad;
    samples_.push_back({time_s, sideways_m_});
    const double cut_s = time_s - window_s_ + 1e-9;
    while (samples_.size() >= 2 && samples_[1].time_s <= cut_s) samples_.pop_front();
    const Sample& first = samples_.front();
    if (first.time_s > cut_s) return std::nullopt;
    return std::abs(sideways_m_ - first.sideways_m) / (time_s - first.time_s);
  }

 private:
  struct Sample {
    double time_s, sideways_m;
  };
  double window_s_;
  std::deque<Sample> samples_;
  double sideways_m_ = 0.0;
  double last_x_m_ = 0.0, last_y_m_ = 0.0, last_yaw_rad_ = 0.0;
};

}  // namespace marsokhod::runner
