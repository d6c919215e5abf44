// The gyro's null drift over a leg in motion, taken back out of the dead-reckoned heading when
// the rover stands again (a zero-velocity update for the heading).
//
// The ADIS16100's null drifts with temperature at up to 0.01 LSB/s (chapter 3.3), and (3.4)
// learns it only while the rover stands: while it moves, ω = 0.0170·(y − yaw) uses the null y
// learnt before, so a leg of T seconds turns the heading by up to ½·0.01·T²·0.0170 rad (0.019 rad
// for a 15-s move) — the largest error of the dead reckoning on hard ground. Each standing period
// measures the null itself: its readings' mean m at their mean time t (the rover still, the true
// rate is 0). Between two such anchors (t_a, m_a) and (t_b, m_b) the null is taken linear,
//   ŷ(t) = m_a + (m_b − m_a)·(t − t_a)/(t_b − t_a),
// and the heading the readings of the moving cycles k (period h_k, null used y_k) gained is
//   Δψ = 0.0170·Σ h_k·(ŷ(t_k) − y_k)
// (ω_true − ω_used = 0.0170·(ŷ − y)). The position drifted with it: at cycle k the heading was
// off by c_k = 0.0170·Σ_{j≤k} h_j·(ŷ(t_j) − y_j) = 0.0170·(A_k + s·B_k), with
// A_k = Σ_{j≤k} h_j·(m_a − y_j), B_k = Σ_{j≤k} h_j·(t_j − t_a) and the slope
// s = (m_b − m_a)/(t_b − t_a) known only at the leg's end; a step Δs_k driven along ψ_k went
// c_k·Δs_k to its side (small angles), so the position's correction is
//   Δp = 0.0170·(U + s·V),  U = Σ Δs_k·A_k·n_k,  V = Σ Δs_k·B_k·n_k,  n_k = (−sin ψ_k, cos ψ_k)
// summed as the leg goes (add_motion), exact to first order in c. Δψ is applied as soon as the new standing period has
// min_samples readings and refined with each further one (its mean sharpens) until the rover
// moves again; then (t_b, m_b) becomes the next leg's anchor a. A leg without an anchor before it
// (after a standing period shorter than min_samples) is not corrected, and a standing period
// shorter than min_samples does not end the leg. The readings count from the driver's first
// cycle, so the rover's standing during its start-up anchors the first leg; begin_leg() starts
// the leg at the odometry's origin (what moved before it is no part of the pose).
#pragma once

#include <cstddef>

namespace marsokhod::estimation {

// What to add to the pose now: heading [rad] and position [m] in the odometry frame.
struct PoseCorrection {
  double heading_rad = 0.0;
  double x_m = 0.0;
  double y_m = 0.0;
  bool operator==(const PoseCorrection&) const = default;
};

class NullDriftCorrection {
 public:
  // radps_per_count: the gyro's scale of (3.4); min_samples: readings that make an anchor.
  // Throws std::invalid_argument unless radps_per_count > 0 is finite and min_samples ≥ 1.
  NullDriftCorrection(double radps_per_count, std::size_t min_samples);

  // One gyro reading at time t [s], the cycle's period h, the raw reading yaw [counts], the null
  // y the reading was converted with [counts], and whether the rover stood still. Returns what
  // to add to the pose now (zero mostly). Throws std::invalid_argument on a non-finite argument
  // or h ≤ 0.
  PoseCorrection update(double time_s, double period_s, double yaw_counts,
                        double null_used_counts, bool still);

  // The pose's step of this cycle, after update: Δs [m] driven along the heading ψ [rad].
  // Throws std::invalid_argument on a non-finite argument.
  void add_motion(double distance_m, double heading_rad);

  // The leg starts now: what moved before is forgotten, the anchor and a standing period in
  // progress are kept.
  void begin_leg();

  // How long the rover has stood still so far [s] (0 while it moves): the last still reading's
  // time − the first's + its period.
  double standing_s() const { return was_still_ ? still_last_s_ - still_first_s_ : 0.0; }

  // The correction applied to the last leg so far [rad].
  double last_correction_rad() const { return applied_rad_; }

 private:
  void end_standing();

  double scale_;
  std::size_t min_samples_;
  // The standing period now (or the last one): its readings' count, Σ yaw, Σ t.
  std::size_t still_n_ = 0;
  double still_sum_ = 0.0, still_time_sum_ = 0.0;
  bool was_still_ = false;
  double still_first_s_ = 0.0, still_last_s_ = 0.0;  // still_first_s_: minus the first period
  // Anchor a: the standing period before the leg.
  bool anchored_ = false;
  double anchor_time_s_ = 0.0, anchor_counts_ = 0.0;
  // The leg since anchor a: Σh, Σh·y, Σh·t of the moving readings.
  double moving_s_ = 0.0, moving_null_sum_ = 0.0, moving_time_sum_ = 0.0;
  // U and V of the leg (x, y each).
  double u_x_ = 0.0, u_y_ = 0.0, v_x_ = 0.0, v_y_ = 0.0;
  double applied_rad_ = 0.0;  // what was added for this leg so far
  double applied_x_m_ = 0.0, applied_y_m_ = 0.0;
};

}  // namespace marsokhod::estimation
