#include "core/estimation/null_drift.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/checks/checks.hpp"

namespace marsokhod::estimation {

NullDriftCorrection::NullDriftCorrection(double radps_per_count, std::size_t min_samples)
    : scale_(radps_per_count), min_samples_(min_samples) {
  if (!(std::isfinite(radps_per_count) && radps_per_count > 0.0)) {
    throw std::invalid_argument("NullDriftCorrection: the gyro's scale must be > 0 rad/s per count");
  }
  if (min_samples == 0) {
    throw std::invalid_argument("NullDriftCorrection: an anchor needs at least one reading");
  }
}

void NullDriftCorrection::end_standing() {
  if (still_n_ < min_samples_) return;  // too short to measure the null: the leg goes on
  const double n = static_cast<double>(still_n_);
  anchored_ = true;
  anchor_time_s_ = still_time_sum_ / n;
  anchor_counts_ = still_sum_ / n;
  begin_leg();
}

void NullDriftCorrection::begin_leg() {
  moving_s_ = moving_null_sum_ = moving_time_sum_ = 0.0;
  u_x_ = u_y_ = v_x_ = v_y_ = 0.0;
  applied_rad_ = applied_x_m_ = applied_y_m_ = 0.0;
}

void NullDriftCorrection::add_motion(double distance_m, double heading_rad) {
  constexpr std::string_view kLaw = "NullDriftCorrection::add_motion";
  checks::law::require_finite(distance_m, kLaw, "distance_m");
  checks::law::require_finite(heading_rad, kLaw, "heading_rad");
  if (!anchored_ || moving_s_ <= 0.0) return;  // no leg to correct (yet)
  const double a = anchor_counts_ * moving_s_ - moving_null_sum_;
  const double b = moving_time_sum_ - anchor_time_s_ * moving_s_;
  const double nx = -std::sin(heading_rad) * distance_m;
  const double ny = std::cos(heading_rad) * distance_m;
  u_x_ += a * nx;
  u_y_ += a * ny;
  v_x_ += b * nx;
  v_y_ += b * ny;
}

PoseCorrection NullDriftCorrection::update(double time_s, double period_s, double yaw_counts,
                                           double null_used_counts, bool still) {
  constexpr std::string_view kLaw = "NullDriftCorrection::update";
  checks::law::require_finite(time_s, kLaw, "time_s");
  checks::law::require_finite(period_s, kLaw, "period_s");
  checks::law::require_finite(yaw_counts, kLaw, "yaw_counts");
  checks::law::require_finite(null_used_counts, kLaw, "null_used_counts");
  if (!(period_s > 0.0)) {
    throw std::invalid_argument("NullDriftCorrection::update: period_s must be > 0, got " +
                                std::to_string(period_s));
  }
  if (!still) {
    if (was_still_) end_standing();
    was_still_ = false;
    moving_s_ += period_s;
    moving_null_sum_ += period_s * null_used_counts;
    moving_time_sum_ += period_s * time_s;
    return {};
  }
  if (!was_still_) {
    still_n_ = 0;
    still_sum_ = still_time_sum_ = 0.0;
    still_first_s_ = time_s - period_s;
  }
  still_last_s_ = time_s;
  was_still_ = true;
  ++still_n_;
  still_sum_ += yaw_counts;
  still_time_sum_ += time_s;
  if (!anchored_ || moving_s_ <= 0.0 || still_n_ < min_samples_) return {};
  const double n = static_cast<double>(still_n_);
  const double t_b = still_time_sum_ / n;
  const double m_b = still_sum_ / n;
  if (!(t_b > anchor_time_s_)) return {};
  // Σ h·(ŷ(t_k) − y_k) over the moving readings = A + s·B, ŷ linear between the anchors.
  const double slope = (m_b - anchor_counts_) / (t_b - anchor_time_s_);
  const double a = anchor_counts_ * moving_s_ - moving_null_sum_;
  const double b = moving_time_sum_ - anchor_time_s_ * moving_s_;
  const double heading = scale_ * (a + slope * b);
  const double x = scale_ * (u_x_ + slope * v_x_);
  const double y = scale_ * (u_y_ + slope * v_y_);
  const PoseCorrection delta{heading - applied_rad_, x - applied_x_m_, y - applied_y_m_};
  applied_rad_ = heading;
  applied_x_m_ = x;
  applied_y_m_ = y;
  return delta;
}

}  // namespace marsokhod::estimation
