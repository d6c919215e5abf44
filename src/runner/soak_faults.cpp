#include "runner/soak_faults.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace marsokhod::runner {
namespace {

constexpr double kFrameLoss = 0.01;  // the 1 %

std::int64_t seconds_us(double s) { return std::llround(s * 1e6); }

}  // namespace

const char* fault_kind_name(FaultKind kind) {
  switch (kind) {
    case FaultKind::kFrameLoss: return "frame-loss";
    case FaultKind::kLostPulses: return "lost-pulses";
    case FaultKind::kSilentController: return "silent-controller";
    case FaultKind::kBatterySag: return "battery-sag";
    case FaultKind::kBlockedWheel: return "blocked-wheel";
    case FaultKind::kWheelInAir: return "wheel-in-air";
    case FaultKind::kBrownout: return "brown-out";
  }
  return "?";
}

FaultSchedule::FaultSchedule(std::uint64_t seed) : random_(seed) {
  next_us_ = seconds_us(random_.uniform(10.0, 30.0));  // start-up first
}

FaultChange FaultSchedule::switch_on(FaultKind kind, std::int64_t time_us, sim::SimFaults& f) {
  char what[80] = "";
  std::size_t target = 0;
  switch (kind) {
    case FaultKind::kFrameLoss:
      f.frame_loss_probability = kFrameLoss;
      std::snprintf(what, sizeof what, "%.0f %% frame loss", kFrameLoss * 100.0);
      break;
    case FaultKind::kLostPulses: {
      target = random_.below(kMotorCount);
      const double fraction = random_.uniform(0.05, 0.5);
      f.lost_pulse_fraction[target] = fraction;
      std::snprintf(what, sizeof what, "µ%zu loses %.0f %% of its encoder pulses", target,
                    fraction * 100.0);
      break;
    }
    case FaultKind::kSilentController:
      target = random_.below(kMotorCount + 1);
      f.silent[target] = true;
      std::snprintf(what, sizeof what, "µ%zu silent", target);
      break;
    case FaultKind::kBatterySag: {
      const double ohm = random_.uniform(0.2, 0.8);
      f.extra_series_resistance_ohm = ohm;
      std::snprintf(what, sizeof what, "battery sag %.2f Ω", ohm);
      break;
    }
    case FaultKind::kBlockedWheel:
      target = random_.below(kWheelCount);
      f.wheel_blocked[target] = true;
      std::snprintf(what, sizeof what, "wheel %zu blocked", target);
      break;
    case FaultKind::kWheelInAir:
      target = random_.below(kWheelCount);
      f.wheel_no_contact[target] = true;
      std::snprintf(what, sizeof what, "wheel %zu in the air", target);
      break;
    case FaultKind::kBrownout: std::snprintf(what, sizeof what, "brown-out"); break;
  }
  if (kind != FaultKind::kBrownout) {
    active_.push_back({kind, time_us + seconds_us(random_.uniform(5.0, 45.0)), target, what});
  }
  ++injected_[static_cast<std::size_t>(kind)];
  return {kind, true, what};
}

void FaultSchedule::switch_off(const Active& a, sim::SimFaults& f) {
  switch (a.kind) {
    case FaultKind::kFrameLoss: f.frame_loss_probability = 0.0; break;
    case FaultKind::kLostPulses: f.lost_pulse_fraction[a.target] = 0.0; break;
    case FaultKind::kSilentController: f.silent[a.target] = false; break;
    case FaultKind::kBatterySag: f.extra_series_resistance_ohm = 0.0; break;
    case FaultKind::kBlockedWheel: f.wheel_blocked[a.target] = false; break;
    case FaultKind::kWheelInAir: f.wheel_no_contact[a.target] = false; break;
    case FaultKind::kBrownout: break;
  }
}

std::vector<FaultChange> FaultSchedule::update(std::int64_t time_us, sim::SimulatedRover& rover) {
  const std::int64_t elapsed_us = time_us - last_us_;
  last_us_ = time_us;
  for (const Active& a : active_) active_us_[static_cast<std::size_t>(a.kind)] += elapsed_us;
  if (!computer_was_on_) active_us_[static_cast<std::size_t>(FaultKind::kBrownout)] += elapsed_us;
  computer_was_on_ = rover.computer_on();
  std::vector<FaultChange> changes;
  sim::SimFaults faults = rover.faults();
  const auto ended = std::stable_partition(active_.begin(), active_.end(),
                                           [time_us](const Active& a) { return a.until_us > time_us; });
  for (auto it = ended; it != active_.end(); ++it) {
    switch_off(*it, faults);
    changes.push_back({it->kind, false, it->what});
  }
  active_.erase(ended, active_.end());
  if (time_us >= next_us_) {
    next_us_ = time_us + seconds_us(random_.uniform(10.0, 50.0));
    const auto kind = static_cast<FaultKind>(random_.below(kFaultKindCount));
    const bool busy = std::any_of(active_.begin(), active_.end(),
                                  [kind](const Active& a) { return a.kind == kind; });
    // One fault of a kind at a time; a brown-out only while the computer runs.
    if (!busy && (kind != FaultKind::kBrownout || rover.computer_on())) {
      changes.push_back(switch_on(kind, time_us, faults));
      if (kind == FaultKind::kBrownout) rover.force_brownout();
    }
  }
  if (!changes.empty()) rover.set_faults(faults);
  return changes;
}

std::array<double, kFaultKindCount> FaultSchedule::active_s() const {
  std::array<double, kFaultKindCount> out{};
  for (std::size_t k = 0; k < kFaultKindCount; ++k) out[k] = static_cast<double>(active_us_[k]) * 1e-6;
  return out;
}

}  // namespace marsokhod::runner
