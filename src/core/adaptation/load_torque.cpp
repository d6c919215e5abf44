#include "core/adaptation/load_torque.hpp"

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

}  // namespace marsokhod::adaptation
