#include "core/adaptation/voltage_drop.hpp"

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "core/checks/checks.hpp"

namespace marsokhod::adaptation {

double voltage_drop_v(std::span<const double> duties, std::span<const double> loads_radps,
                      const PowerParams& power) {
  if (duties.size() != loads_radps.size()) {
    throw std::invalid_argument("voltage_drop_v: " + std::to_string(duties.size()) +
                                " duties but " + std::to_string(loads_radps.size()) +
                                " loads; pass one of each per motor");
  }
  checks::require_non_negative(power.duty_drop_v, "voltage_drop_v", "power.duty_drop_v");
  checks::require_non_negative(power.load_drop_v_s2_per_rad2, "voltage_drop_v",
                               "power.load_drop_v_s2_per_rad2");
  double duty_sum = 0.0;
  double load_square_sum_rad2_per_s2 = 0.0;
  for (std::size_t i = 0; i < duties.size(); ++i) {
    checks::require_duty(duties[i], "voltage_drop_v", checks::Element{"duties", i});
    checks::require_finite(loads_radps[i], "voltage_drop_v",
                           checks::Element{"loads_radps", i});
    duty_sum += std::abs(duties[i]);
    load_square_sum_rad2_per_s2 += loads_radps[i] * loads_radps[i];
  }
  const double drop_v =
      power.duty_drop_v * duty_sum + power.load_drop_v_s2_per_rad2 * load_square_sum_rad2_per_s2;
  checks::require_finite_result(drop_v, "voltage_drop_v", "drop_v");
  return drop_v;
}

}  // namespace marsokhod::adaptation
