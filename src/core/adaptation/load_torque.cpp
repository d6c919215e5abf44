#include "core/adaptation/load_torque.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/checks/checks.hpp"

namespace marsokhod::adaptation {
namespace {

void check_gains(const char* function, double duty, const LoadParams& load) {
  checks::require_duty(duty, function, "duty");
  checks::require_positive(load.gain_same_sign_radps_per_nm, function,
                           "load.gain_same_sign_radps_per_nm");
  checks::require_positive(load.gain_opposite_sign_radps_per_nm, function,
                           "load.gain_opposite_sign_radps_per_nm");
}

// B^(sgn(x d)) for x = τ or x = l, which share their sign. Compares signs rather than the
// product, which can underflow to 0 for tiny values.
double gain_radps_per_nm(double signed_value, double duty, const LoadParams& load) {
  const bool opposite = (signed_value > 0.0 && duty < 0.0) || (signed_value < 0.0 && duty > 0.0);
  return opposite ? load.gain_opposite_sign_radps_per_nm : load.gain_same_sign_radps_per_nm;
}

}  // namespace

double load_from_torque(double torque_nm, double duty, const LoadParams& load) {
  checks::require_finite(torque_nm, "load_from_torque", "torque_nm");
  check_gains("load_from_torque", duty, load);
  const double load_radps = torque_nm * gain_radps_per_nm(torque_nm, duty, load);
  checks::require_finite_result(load_radps, "load_from_torque", "load_radps");
  return load_radps;
}

double torque_from_load(double load_radps, double duty, const LoadParams& load) {
  checks::require_finite(load_radps, "torque_from_load", "load_radps");
  check_gains("torque_from_load", duty, load);
  const double torque_nm = load_radps / gain_radps_per_nm(load_radps, duty, load);
  checks::require_finite_result(torque_nm, "torque_from_load", "torque_nm");
  return torque_nm;
}

namespace {

// The column at |d|: linear between the entries, constant beyond the ends.
double interpolate(const std::vector<double>& duty, const std::vector<double>& values,
                   double magnitude) {
  if (magnitude <= duty.front()) return values.front();
  if (magnitude >= duty.back()) return values.back();
  const auto upper = std::upper_bound(duty.begin(), duty.end(), magnitude);
  const std::size_t i = static_cast<std::size_t>(upper - duty.begin());
  const double t = (magnitude - duty[i - 1]) / (duty[i] - duty[i - 1]);
  return values[i - 1] + t * (values[i] - values[i - 1]);
}

}  // namespace

LoadParams gains_at(const LoadGainParams& table, double duty) {
  checks::require_duty(duty, "gains_at", "duty");
  if (table.duty.empty() || table.same_sign_radps_per_nm.size() != table.duty.size() ||
      table.opposite_sign_radps_per_nm.size() != table.duty.size()) {
    throw std::invalid_argument(
        "gains_at: the B± table of icr " + std::to_string(table.icr) +
        " needs as many B⁺ and B⁻ values as duty cycles, at least one (a [[load_gain]] table)");
  }
  const double magnitude = std::abs(duty);
  return {interpolate(table.duty, table.same_sign_radps_per_nm, magnitude),
          interpolate(table.duty, table.opposite_sign_radps_per_nm, magnitude)};
}

const LoadGainParams& select_load_gains(const std::vector<LoadGainParams>& tables, int icr) {
  std::string available;
  for (const LoadGainParams& t : tables) {
    if (t.icr == icr) return t;
    available += (available.empty() ? "" : ", ") + std::to_string(t.icr);
  }
  throw std::invalid_argument("select_load_gains: no [[load_gain]] table for icr " +
                              std::to_string(icr) + " (tables for: " +
                              (available.empty() ? "none" : available) + ")");
}

double torque_estimate_nm(double load_radps, double duty, const LoadGainParams& table) {
  if (!std::isfinite(load_radps)) return std::numeric_limits<double>::quiet_NaN();
  return torque_from_load(load_radps, duty, gains_at(table, duty));
}

}  // namespace marsokhod::adaptation
