#include "core/behaviour/power_management.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/checks/checks.hpp"

namespace marsokhod::behaviour {
namespace {

void require_power_params(const PowerParams& power, const char* function) {
  checks::require_positive(power.duty_drop_v, function, "power.duty_drop_v");
  checks::require_non_negative(power.load_drop_v_s2_per_rad2, function,
                               "power.load_drop_v_s2_per_rad2");
  checks::require_non_negative(power.max_drop_v, function, "power.max_drop_v");
}

}  // namespace

double equal_duty_bound(double load_square_sum_rad2_per_s2, std::size_t motor_count,
                        const PowerParams& power) {
  constexpr const char* kFunction = "equal_duty_bound";
  require_power_params(power, kFunction);
  checks::require_non_negative(load_square_sum_rad2_per_s2, kFunction,
                               "load_square_sum_rad2_per_s2");
  if (motor_count == 0) {
    throw std::invalid_argument(
        "equal_duty_bound: motor_count = 0; pass the number of motors sharing the budget "
        "(8 as printed in (6.1), 6 for Example 6.1)");
  }
  return (power.max_drop_v - power.load_drop_v_s2_per_rad2 * load_square_sum_rad2_per_s2) /
         (static_cast<double>(motor_count) * power.duty_drop_v);
}

double next_duty_bound(const MotorVector& duties, const MotorVector& loads_radps,
                       const PowerParams& power, const BehaviourSwitches& switches,
                       double unmodelled_drop_v) {
  constexpr const char* kFunction = "next_duty_bound";
  require_power_params(power, kFunction);
  checks::require_non_negative(unmodelled_drop_v, kFunction, "unmodelled_drop_v");
  double largest_duty = 0.0;
  double duty_sum = 0.0;
  double load_square_sum_rad2_per_s2 = 0.0;
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    checks::require_within(duties[i], -1.0, 1.0, kFunction, checks::Element{"duties", i});
    checks::require_finite_estimate(loads_radps[i], kFunction,
                                    checks::Element{"loads_radps", i});
    largest_duty = std::max(largest_duty, std::abs(duties[i]));
    duty_sum += std::abs(duties[i]);
    load_square_sum_rad2_per_s2 += loads_radps[i] * loads_radps[i];
  }
  if (!switches.power_management || duty_sum == 0.0) {
    return 1.0;
  }
  // Loads so large that Σ l² overflows make the budget −inf, which the floor catches like any
  // other overspent budget; Ξ = 0 ignores the loads (and must not turn 0 · inf into NaN).
  const double load_drop_v = power.load_drop_v_s2_per_rad2 == 0.0
                                 ? 0.0
                                 : power.load_drop_v_s2_per_rad2 * load_square_sum_rad2_per_s2;
  const double budget_v = power.max_drop_v - load_drop_v - unmodelled_drop_v;
  const double bound = largest_duty / duty_sum * budget_v / power.duty_drop_v;
  return std::clamp(bound, kMinimumDutyBound, 1.0);
}

double MeasuredDropExcess::update(double measured_drop_v, double modelled_drop_v,
                                  double period_s) {
  constexpr const char* kFunction = "MeasuredDropExcess::update";
  checks::require_finite(measured_drop_v, kFunction, "measured_drop_v");
  checks::require_finite(modelled_drop_v, kFunction, "modelled_drop_v");
  checks::require_positive(period_s, kFunction, "period_s");
  const double excess_v = std::max(0.0, measured_drop_v - modelled_drop_v);
  const double released_v = excess_v_ * std::exp(-period_s / kDropExcessReleaseS);
  excess_v_ = std::max(excess_v, released_v);
  return excess_v_;
}

}  // namespace marsokhod::behaviour
