#include "core/estimation/failsafes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/checks/checks.hpp"

namespace marsokhod::estimation {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;
constexpr double kMinReadingMps2 = 0.981;  // a tenth of g

bool in_range(double v, double lo, double hi) { return std::isfinite(v) && v > lo && v <= hi; }

// The limits a stall check shares (stuck, joint blocked): T ≥ 0 (0: off), ν_min > 0, s in [0, 1).
void validate_stall_limits(std::string_view who, double time_s, double min_command_radps,
                           double turning_share) {
  checks::law::require_finite(time_s, who, "time_s");
  if (time_s < 0.0) {
    throw std::invalid_argument(std::string(who) +
                                ": time_s must be ≥ 0 (0 switches the check off), got " +
                                checks::format_number(time_s));
  }
  checks::law::require_positive(min_command_radps, who, "min_command_radps");
  if (!(std::isfinite(turning_share) && turning_share >= 0.0 && turning_share < 1.0)) {
    throw std::invalid_argument(std::string(who) + ": turning_share must lie in [0, 1), got " +
                                checks::format_number(turning_share));
  }
}

}  // namespace

TipOverMonitor::TipOverMonitor(TipOverLimits limits) : limits_(limits) {
  constexpr double kHalfPi = std::numbers::pi / 2.0;
  if (!in_range(limits.roll_rad, 0.0, kHalfPi) || !in_range(limits.pitch_rad, 0.0, kHalfPi)) {
    throw std::invalid_argument("TipOverMonitor: the roll and pitch limits must lie in (0, π/2] rad, got " +
                                checks::format_number(limits.roll_rad) + " and " +
                                checks::format_number(limits.pitch_rad));
  }
  checks::law::require_positive(limits.time_constant_s, "TipOverMonitor", "time_constant_s");
}

std::optional<std::string> TipOverMonitor::update(const std::array<double, 3>& a,
                                                  double period_s) {
  constexpr std::string_view kLaw = "TipOverMonitor::update";
  checks::law::require_positive(period_s, kLaw, "period_s");
  for (std::size_t i = 0; i < 3; ++i) {
    checks::law::require_finite(a[i], kLaw, checks::Element{"accel_mps2", i});
  }
  if (std::hypot(a[0], a[1], a[2]) >= kMinReadingMps2) {
    const double alpha = std::min(1.0, period_s / limits_.time_constant_s);
    for (std::size_t i = 0; i < 3; ++i) mean_mps2_[i] += alpha * (a[i] - mean_mps2_[i]);
  }
  const auto& m = mean_mps2_;
  attitude_.roll_rad = std::atan2(-m[1], -m[2]);
  attitude_.pitch_rad = std::atan2(m[0], std::hypot(m[1], m[2]));
  const bool roll = std::abs(attitude_.roll_rad) > limits_.roll_rad;
  const bool pitch = std::abs(attitude_.pitch_rad) > limits_.pitch_rad;
  if (!roll && !pitch) return std::nullopt;
  char text[96];
  std::snprintf(text, sizeof text, "tip-over: %s %.1f° beyond the limit %.1f°",
                roll ? "roll" : "pitch",
                (roll ? attitude_.roll_rad : attitude_.pitch_rad) * kRadToDeg,
                (roll ? limits_.roll_rad : limits_.pitch_rad) * kRadToDeg);
  return std::string(text);
}

StuckMonitor::StuckMonitor(StuckLimits limits) : limits_(limits) {
  validate_stall_limits("StuckMonitor", limits.time_s, limits.min_command_radps,
                        limits.turning_share);
  checks::law::require_positive(limits.min_yaw_rate_radps, "StuckMonitor", "min_yaw_rate_radps");
}

std::optional<std::string> StuckMonitor::update(const StuckInput& in) {
  constexpr std::string_view kLaw = "StuckMonitor::update";
  checks::law::require_positive(in.period_s, kLaw, "period_s");
  checks::law::require_finite(in.yaw_rate_radps, kLaw, "yaw_rate_radps");
  double commanded = 0.0;
  double turned = 0.0;
  for (std::size_t i = 0; i < in.no_load_radps.size(); ++i) {
    checks::law::require_finite(in.no_load_radps[i], kLaw, checks::Element{"no_load_radps", i});
    checks::law::require_finite(in.velocity_radps[i], kLaw,
                                checks::Element{"velocity_radps", i});
    commanded += std::abs(in.no_load_radps[i]);
    turned += std::abs(in.velocity_radps[i]);
  }
  const bool stalled = limits_.time_s > 0.0 && in.driving && in.motion_asked &&
                       commanded >= limits_.min_command_radps * static_cast<double>(in.no_load_radps.size()) &&
                       turned <= limits_.turning_share * commanded &&
                       std::abs(in.yaw_rate_radps) < limits_.min_yaw_rate_radps;
  if (!stalled) {
    stalled_s_ = turned_sum_ = command_sum_ = 0.0;
    return std::nullopt;
  }
  const bool before = stalled_s_ >= limits_.time_s;
  stalled_s_ += in.period_s;
  turned_sum_ += turned * in.period_s;  // weighted by time: a cycle's period may change
  command_sum_ += commanded * in.period_s;
  if (before || stalled_s_ < limits_.time_s) return std::nullopt;
  char text[128];
  std::snprintf(text, sizeof text, "stuck: the centre wheels turned at %.0f %% of their command for %.1f s",
                100.0 * turned_sum_ / command_sum_, stalled_s_);
  return std::string(text);
}

JointBlockedMonitor::JointBlockedMonitor(JointBlockedLimits limits) : limits_(limits) {
  validate_stall_limits("JointBlockedMonitor", limits.time_s, limits.min_command_radps,
                        limits.turning_share);
}

std::vector<std::string> JointBlockedMonitor::update(const JointBlockedInput& in) {
  constexpr std::string_view kLaw = "JointBlockedMonitor::update";
  checks::law::require_positive(in.period_s, kLaw, "period_s");
  for (std::size_t j = 0; j < 2; ++j) {
    checks::law::require_finite(in.no_load_radps[j], kLaw, checks::Element{"no_load_radps", j});
    checks::law::require_finite(in.velocity_radps[j], kLaw, checks::Element{"velocity_radps", j});
  }
  std::vector<std::string> faults;
  for (std::size_t j = 0; j < 2; ++j) {
    const double commanded = std::abs(in.no_load_radps[j]);
    const double turned = std::abs(in.velocity_radps[j]);
    const bool stalled = limits_.time_s > 0.0 && in.driving &&
                         commanded >= limits_.min_command_radps &&
                         turned <= limits_.turning_share * commanded;
    if (!stalled) {
      stalled_s_[j] = turned_sum_[j] = command_sum_[j] = 0.0;
      continue;
    }
    const bool before = stalled_s_[j] >= limits_.time_s;
    stalled_s_[j] += in.period_s;
    turned_sum_[j] += turned * in.period_s;
    command_sum_[j] += commanded * in.period_s;
    if (before || stalled_s_[j] < limits_.time_s) continue;
    char text[128];
    std::snprintf(text, sizeof text,
                  "%s joint blocked: it turned at %.0f %% of its command (%.2f rad/s) for %.1f s",
                  j == 0 ? "front" : "rear", 100.0 * turned_sum_[j] / command_sum_[j],
                  command_sum_[j] / stalled_s_[j], stalled_s_[j]);
    faults.emplace_back(text);
  }
  return faults;
}

}  // namespace marsokhod::estimation
