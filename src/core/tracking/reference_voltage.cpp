#include "core/tracking/reference_voltage.hpp"

#include <algorithm>

#include "core/checks/checks.hpp"

namespace marsokhod::tracking {

ReferenceVoltage::ReferenceVoltage(double lambda) : lambda_(lambda) {
  checks::setting::require_in_range(lambda, 0.0, 1.0, "filters.reference_voltage_lambda");
}

double ReferenceVoltage::update(double supply_v, bool all_duty_zero) {
  checks::setting::require_finite(supply_v, "supply voltage U [V]",
                         "convert µ8's vcc reading with sensors.supply_* before passing it");
  if (!started_) {
    started_ = true;
    reference_v_ = supply_v;
  }
  const double candidate_v =
      all_duty_zero ? lambda_ * reference_v_ + (1.0 - lambda_) * supply_v : reference_v_;
  reference_v_ = std::max(supply_v, candidate_v);
  return reference_v_;
}

}  // namespace marsokhod::tracking
