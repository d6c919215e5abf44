#include "core/adaptation/motor_curve.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "core/checks/checks.hpp"

namespace marsokhod::adaptation {
namespace {

[[noreturn]] void reject_table(int icr, const std::string& problem) {
  throw std::invalid_argument("motor curve for icr " + std::to_string(icr) + ": " + problem +
                              "; fix motor_curves in config/marsokhod.toml (Procedure 4.4)");
}

std::string entry(const char* field, std::size_t index, double value) {
  return checks::argument_name(field, index) + " = " + checks::format_number(value);
}

// 0 = values[0] < values[1] < … (and values.back() = 1 when must_end_at_one); all finite.
void check_axis(const MotorCurveParams& params, const std::vector<double>& values,
                const char* field, bool must_end_at_one) {
  if (values.front() != 0.0) {
    reject_table(params.icr, entry(field, 0, values.front()) + " must be exactly 0");
  }
  for (std::size_t i = 1; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      reject_table(params.icr, entry(field, i, values[i]) + " must be finite");
    }
    if (!(values[i] > values[i - 1])) {
      reject_table(params.icr, entry(field, i, values[i]) + " must be greater than " +
                                   entry(field, i - 1, values[i - 1]) + " (strictly increasing)");
    }
  }
  if (must_end_at_one && values.back() != 1.0) {
    reject_table(params.icr, entry(field, values.size() - 1, values.back()) + " must be exactly 1");
  }
}

void check_table(const MotorCurveParams& params) {
  if (params.duty.size() != params.no_load_speed_radps.size()) {
    reject_table(params.icr, "duty has " + std::to_string(params.duty.size()) +
                                 " entries but no_load_speed_radps has " +
                                 std::to_string(params.no_load_speed_radps.size()) +
                                 "; they must pair up");
  }
  if (params.duty.size() < 2) {
    reject_table(params.icr, "duty has " + std::to_string(params.duty.size()) +
                                 " entries; at least 2 are needed (d = 0 and d = 1)");
  }
  if (params.icr < 255 || params.icr > 2047) {
    reject_table(params.icr, "icr must lie in 255..2047 (chapter 3.2)");
  }
  check_axis(params, params.duty, "duty", true);
  check_axis(params, params.no_load_speed_radps, "no_load_speed_radps", false);
}

// Interpolates y(x) for 0 ≤ x ≤ xs.back() over strictly increasing nodes; exact at the nodes.
double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  const auto upper = std::upper_bound(xs.begin(), xs.end(), x);
  if (upper == xs.end()) {
    return ys.back();
  }
  const auto i = static_cast<std::size_t>(upper - xs.begin()) - 1;
  if (x == xs[i]) {
    return ys[i];
  }
  const double t = (x - xs[i]) / (xs[i + 1] - xs[i]);
  return std::clamp(ys[i] + t * (ys[i + 1] - ys[i]), ys[i], ys[i + 1]);
}

// The odd extension with saturation: f(−x) = −f(x), |x| ≥ xs.back() → ±ys.back().
double odd_interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  const double magnitude = std::abs(x) >= xs.back() ? ys.back() : interpolate(xs, ys, std::abs(x));
  return x < 0.0 ? -magnitude : magnitude;
}

}  // namespace

MotorCurve::MotorCurve(const MotorCurveParams& params)
    : icr_(params.icr), duty_(params.duty), velocity_radps_(params.no_load_speed_radps) {
  check_table(params);
}

double MotorCurve::velocity_radps(double duty) const {
  checks::require_finite(duty, "MotorCurve::velocity_radps", "duty");
  return odd_interpolate(duty_, velocity_radps_, duty);
}

double MotorCurve::duty(double velocity_radps) const {
  checks::require_finite(velocity_radps, "MotorCurve::duty", "velocity_radps");
  return odd_interpolate(velocity_radps_, duty_, velocity_radps);
}

const MotorCurveParams& select_motor_curve(const std::vector<MotorCurveParams>& curves, int icr) {
  for (const MotorCurveParams& curve : curves) {
    if (curve.icr == icr) {
      return curve;
    }
  }
  std::string available;
  for (const MotorCurveParams& curve : curves) {
    available += (available.empty() ? "" : ", ") + std::to_string(curve.icr);
  }
  throw std::invalid_argument("no motor curve for icr " + std::to_string(icr) +
                              " (available: " + (available.empty() ? "none" : available) +
                              "); add one to motor_curves (Procedure 4.4) or set cycle.icr to "
                              "an available value");
}

}  // namespace marsokhod::adaptation
