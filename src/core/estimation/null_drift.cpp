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
  moving_s_ = moving_null_sum_ = moving_time_sum_ = 0.0;
  applied_rad_ = 0.0;
}

double NullDriftCorrection::update(double time_s, double period_s, double yaw_counts,
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
    return 0.0;
  }
  if (!was_still_) {
    still_n_ = 0;
    still_sum_ = still_time_sum_ = 0.0;
  }
  was_still_ = true;
  ++still_n_;
  still_sum_ += yaw_counts;
  still_time_sum_ += time_s;
  if (!anchored_ || moving_s_ <= 0.0 || still_n_ < min_samples_) return 0.0;
  const double n = static_cast<double>(still_n_);
  const double t_b = still_time_sum_ / n;
  const double m_b = still_sum_ / n;
  if (!(t_b > anchor_time_s_)) return 0.0;
  // Σ h·ŷ(t_k) over the moving readings, ŷ linear between the anchors.
  const double null_integral =
      anchor_counts_ * moving_s_ +
      (m_b - anchor_counts_) * (moving_time_sum_ - anchor_time_s_ * moving_s_) / (t_b - anchor_time_s_);
  const double correction = scale_ * (null_integral - moving_null_sum_);
  const double delta = correction - applied_rad_;
  applied_rad_ = correction;
  return delta;
}

}  // namespace marsokhod::estimation
