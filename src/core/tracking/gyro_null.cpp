#include "core/tracking/gyro_null.hpp"

#include <algorithm>

#include "core/checks/checks.hpp"

namespace marsokhod::tracking {

GyroNullFilter::GyroNullFilter(double initial_counts, double lambda)
    : null_counts_(initial_counts), lambda_(lambda) {
  checks::setting::require_finite(initial_counts, "sensors.gyro_null_typ_counts");
  checks::setting::require_in_range(lambda, 0.0, 1.0, "filters.gyro_null_lambda");
}

double GyroNullFilter::update(double yaw_counts, bool rover_still) {
  checks::setting::require_finite(yaw_counts, "gyro reading yaw",
                                  "pass µ8's 10-bit yaw reading (0..1023)");
  if (rover_still && lambda_ < 1.0) {
    still_samples_ += 1.0;
    const double weight = std::max(1.0 - lambda_, 1.0 / still_samples_);
    null_counts_ = (1.0 - weight) * null_counts_ + weight * yaw_counts;
  }
  return null_counts_;
}

}  // namespace marsokhod::tracking
