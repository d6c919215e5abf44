// The slope hold (our extension of chapters 5.3 and 6.2): on a slope, the wheels of a running
// gait keep the ground they lose downhill.
//
// The driver runs the wheels open loop, as the thesis does: ŵ = W⁻¹ of (4.3), so a motor resists
// a load only along its speed–torque line. A gait's anchors, asked for their compensation speed
// (5.1)/(5.2), are turned downhill by the slope's pull until their motors' line holds it: 0.1
// rad/s of give costs a motor only ≈ 2–3 N·m at an anchor's small duty (B⁺ of (4.7)), 18–27 N at
// the rim against the 248 N that 82 kg weigh along 18°, so on soft sand the anchors roll back
// 0.06–0.17 m a stroke and the gaits climb no steeper than driving (docs/simulator.md).
//
// Per wheel i, the angle lost downhill against the plan, with u = sgn σ (σ > 0 nose up, 6.2.1):
//   e_i^k = clip(e_i^(k−1) + h·u·(ν̂_i^k − w_i^k), 0, E)
//   ŵ_i += u·K·e_i^k
// ν̂ is (4.4)'s response to the planned ŵ (the command without this term), w the measured
// velocity. The term is a spring on the lost angle, not an integrator on the command: a wheel
// that stands where its plan puts it while its motor holds a torque τ needs u·K·e = B·τ more
// command, so it stands e = B·τ/K behind (0.03 rad at K = 10/s and 10 N·m, 4 mm at the rim).
// E bounds what it may ask (K·E = 1 rad/s at the defaults).
//
// One-sided and gated, so that it acts where the open loop gives way and nowhere else:
// - only downhill (e ≥ 0): a wheel ahead of its plan uphill, or behind it downhill, is left to
//   the open loop;
// - only while a gait runs and |σ| is at least the slant dead band (6.2.1): on flat ground the
//   compensation (5.1)/(5.2), worked out on the configured geometry and not the unit's, is no
//   exact kinematics, and a hold there fights it (tried: 0.19 rad of heading lost in
//   odometry-rolking on hard ground, the stuck failsafe tripped against an obstacle);
// - driving keeps the open loop: its wheels slip by design.
// - a wheel's lost angle belongs to its role in the stroke: the driver empties it (reset) when
//   the gait or its state changes or 6.2.3 switches an axle placement (motion_controller.cpp).
// The stall check (estimation/failsafes.hpp) counts the plan's ν, without this term: an anchor
// the hold keeps still on a slope is not a stalled drive.
// Off (or gated out) e is 0 and the term vanishes. K = 0 switches the hold off.
#pragma once

#include "core/params.hpp"

namespace marsokhod::behaviour {

class SlopeHold {
 public:
  // One cycle. `velocity_radps` w and `planned_radps` ν̂ for all eight motors (the joints'
  // entries are ignored); `slope_rad` σ; `gait_running` whether a gait drives the joints this
  // cycle; `period_s` h > 0. Returns the term u·K·e added to each wheel's ŵ (0 on the joints).
  // Throws std::invalid_argument on a non-finite input, h ≤ 0, K < 0 or E < 0; the state is
  // unchanged then.
  MotorVector update(const MotorVector& velocity_radps, const MotorVector& planned_radps,
                     double slope_rad, bool gait_running, double period_s,
                     const BehaviourParams& params);

  // e = 0: the driver is not driving.
  void reset() { lost_rad_ = {}; }

  // e [rad], the angle each wheel has lost downhill (0 on the joints).
  const MotorVector& lost_rad() const { return lost_rad_; }

 private:
  MotorVector lost_rad_{};
};

}  // namespace marsokhod::behaviour
