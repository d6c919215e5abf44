#include "core/tracking/reference_voltage.hpp"

#include <algorithm>
#include <numeric>

#include "core/checks/checks.hpp"

namespace marsokhod::tracking {

ReferenceVoltage::ReferenceVoltage(double lambda) : lambda_(lambda) {
  checks::setting::require_in_range(lambda, 0.0, 1.0, "filters.reference_voltage_lambda");
}

double ReferenceVoltage::mean_supply_v() const {
  if (reading_count_ == 0) return 0.0;
  const auto first = readings_v_.begin();
  return std::accumulate(first, first + static_cast<std::ptrdiff_t>(reading_count_), 0.0) /
         static_cast<double>(reading_count_);
}

double ReferenceVoltage::update(double supply_v, bool all_duty_zero) {
  checks::setting::require_finite(supply_v, "supply voltage U [V]",
                         "convert µ8's vcc reading with sensors.supply_* before passing it");
  started_ = true;
  const bool warming_up = reading_count_ < kSupplyAveragingReadings;
  readings_v_[next_reading_] = supply_v;
  next_reading_ = (next_reading_ + 1) % kSupplyAveragingReadings;
  reading_count_ = std::min(reading_count_ + 1, kSupplyAveragingReadings);
  if (warming_up) {
    reference_v_ = mean_supply_v();  // warming up: no estimate is better than the mean so far
    return reference_v_;
  }
  const double candidate_v =
      all_duty_zero ? lambda_ * reference_v_ + (1.0 - lambda_) * supply_v : reference_v_;
  reference_v_ = std::max(mean_supply_v(), candidate_v);
  return reference_v_;
}

}  // namespace marsokhod::tracking
