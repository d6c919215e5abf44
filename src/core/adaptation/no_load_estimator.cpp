#include "core/adaptation/no_load_estimator.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/checks/checks.hpp"

namespace marsokhod::adaptation {
namespace {

// Absorbs the rounding in |0.0167 − 0.0157| so that a period exactly 1 ms away still matches.
constexpr double kPeriodRounding_s = 1e-12;

std::string describe_pairs(const std::vector<ResponseParams>& responses) {
  std::string pairs;
  for (const ResponseParams& response : responses) {
    pairs += (pairs.empty() ? "(" : ", (") + checks::format_number(response.period_s) + " s, " +
             std::to_string(response.con) + ")";
  }
  return pairs.empty() ? "none" : pairs;
}

void check_all_finite(const MotorVector& values, const char* function, const char* argument) {
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    checks::require_finite(values[i], function, checks::Element{argument, i});
  }
}

}  // namespace

const ResponseParams& select_response(const std::vector<ResponseParams>& responses, double period_s,
                                      int con) {
  checks::require_positive(period_s, "select_response", "period_s");
  const ResponseParams* best = nullptr;
  for (const ResponseParams& response : responses) {
    const double distance_s = std::abs(period_s - response.period_s);
    if (response.con == con && distance_s <= kResponsePeriodTolerance_s + kPeriodRounding_s &&
        (best == nullptr || distance_s < std::abs(period_s - best->period_s))) {
      best = &response;
    }
  }
  if (best == nullptr) {
    throw std::invalid_argument(
        "no δ table (responses) for h = " + checks::format_number(period_s) +
        " s, con = " + std::to_string(con) + ": a table needs the same con and h within " +
        checks::format_number(kResponsePeriodTolerance_s) +
        " s; available (h, con): " + describe_pairs(responses) +
        "; set cycle.period_s and cycle.con to one of them, or run Procedure 4.8 and add a row");
  }
  return *best;
}

NoLoadEstimator::NoLoadEstimator(const ResponseParams& response,
                                 const MotorVector& initial_w_hat_radps)
    : delta_(response.delta) {
  if (delta_.empty()) {
    throw std::invalid_argument(
        "NoLoadEstimator: the δ table for h = " + checks::format_number(response.period_s) +
        " s, con = " + std::to_string(response.con) +
        " is empty; give at least δ⁰ (Procedure 4.8)");
  }
  for (std::size_t j = 0; j < delta_.size(); ++j) {
    checks::require_finite(delta_[j], "NoLoadEstimator", checks::Element{"delta", j});
  }
  check_all_finite(initial_w_hat_radps, "NoLoadEstimator", "initial_w_hat_radps");
  history_.assign(delta_.size() - 1, initial_w_hat_radps);
}

MotorVector NoLoadEstimator::history_sum_radps() const {
  MotorVector sum{};
  const std::size_t length = history_.size();
  for (std::size_t j = 1; j <= length; ++j) {
    // ŵ^(k−j) sits j − 1 places before the newest entry.
    const MotorVector& w_hat = history_[(newest_ + length - (j - 1)) % length];
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      sum[i] += delta_[j] * w_hat[i];
    }
  }
  return sum;
}

MotorVector NoLoadEstimator::no_load_velocity_radps(const MotorVector& w_hat_radps) const {
  check_all_finite(w_hat_radps, "NoLoadEstimator::no_load_velocity_radps", "w_hat_radps");
  MotorVector nu = history_sum_radps();
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    nu[i] += delta_[0] * w_hat_radps[i];
    checks::require_finite_result(nu[i], "NoLoadEstimator::no_load_velocity_radps",
                                  checks::Element{"nu", i});
  }
  return nu;
}

MotorVector NoLoadEstimator::no_load_velocity_radps() const {
  if (delta_[0] != 0.0) {
    throw std::logic_error("NoLoadEstimator: δ⁰ = " + checks::format_number(delta_[0]) +
                           " weighs this cycle's command; call no_load_velocity_radps(w_hat)");
  }
  const MotorVector nu = history_sum_radps();
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    checks::require_finite_result(nu[i], "NoLoadEstimator::no_load_velocity_radps",
                                  checks::Element{"nu", i});
  }
  return nu;
}

void NoLoadEstimator::push(const MotorVector& w_hat_radps) {
  check_all_finite(w_hat_radps, "NoLoadEstimator::push", "w_hat_radps");
  if (history_.empty()) {
    return;
  }
  newest_ = (newest_ + 1) % history_.size();
  history_[newest_] = w_hat_radps;
}

double load(double measured_velocity_radps, double no_load_velocity_radps) {
  checks::require_finite(measured_velocity_radps, "load", "measured_velocity_radps");
  checks::require_finite(no_load_velocity_radps, "load", "no_load_velocity_radps");
  const double load_radps = measured_velocity_radps - no_load_velocity_radps;
  checks::require_finite_result(load_radps, "load", "w - nu");
  return load_radps;
}

MotorVector load(const MotorVector& measured_velocity_radps,
                 const MotorVector& no_load_velocity_radps) {
  MotorVector result{};
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    checks::require_finite(measured_velocity_radps[i], "load",
                           checks::Element{"measured_velocity_radps", i});
    checks::require_finite(no_load_velocity_radps[i], "load",
                           checks::Element{"no_load_velocity_radps", i});
  }
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    result[i] = load(measured_velocity_radps[i], no_load_velocity_radps[i]);
  }
  return result;
}

}  // namespace marsokhod::adaptation
