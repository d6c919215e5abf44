// Procedure 4.4's fit: W_icr(d) from the sweep's samples (motor_curve.hpp).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "calibration/fit.hpp"
#include "calibration/motor_curve.hpp"
#include "calibration/procedure.hpp"

namespace marsokhod::calibration {
namespace {

void check_settings(const std::vector<MotorCurveSample>& samples,
                    const MotorCurveFitSettings& settings) {
  const std::vector<double>& grid = settings.duty_grid;
  if (grid.size() < 2 || grid.front() != 0.0 || grid.back() != 1.0) {
    throw std::invalid_argument("fit_motor_curve: the duty grid must run from 0 to 1");
  }
  for (std::size_t g = 1; g < grid.size(); ++g) {
    if (!(grid[g] > grid[g - 1])) {
      throw std::invalid_argument("fit_motor_curve: the duty grid must be strictly increasing");
    }
  }
  if (!(settings.nominal_supply_v > 0.0) || !(settings.window_duty > 0.0)) {
    throw std::invalid_argument("fit_motor_curve: Ū and the window must be positive");
  }
  for (const MotorCurveSample& s : samples) {
    if (s.velocity_radps.size() != samples.front().velocity_radps.size()) {
      throw std::invalid_argument("fit_motor_curve: samples with different numbers of wheels");
    }
  }
}

// W_i at duty g on one way of the sweep: a line through the samples within the window.
struct WindowFit {
  bool ok = false;
  double value = 0.0;
  std::size_t count = 0;
  std::vector<double> residuals;
};

WindowFit fit_window(const std::vector<MotorCurveSample>& samples, std::size_t wheel, double g,
                     bool rising, const MotorCurveFitSettings& settings) {
  std::vector<double> x;
  std::vector<double> y;
  for (const MotorCurveSample& s : samples) {
    const bool way = s.phase == SweepPhase::kTop ||
                     (rising ? s.phase == SweepPhase::kRising : s.phase == SweepPhase::kFalling);
    if (!way || std::abs(s.duty - g) > settings.window_duty || !(s.supply_v > 0.0)) continue;
    x.push_back(s.duty);
    y.push_back(s.velocity_radps[wheel] * settings.nominal_supply_v / s.supply_v);
  }
  WindowFit out;
  out.count = x.size();
  if (x.size() < settings.min_window_samples) return out;
  try {
    const LineFit line = fit_line(x, y);
    out.value = line.gain * g + line.offset;
    for (std::size_t k = 0; k < x.size(); ++k) {
      out.residuals.push_back(y[k] - (line.gain * x[k] + line.offset));
    }
    out.ok = std::isfinite(out.value);
  } catch (const std::invalid_argument&) {
    // The duty did not vary within the window (a held duty): take the mean.
    out.value = mean(y);
    for (const double v : y) out.residuals.push_back(v - out.value);
    out.ok = std::isfinite(out.value);
  }
  return out;
}

// The mean supply voltage; a problem when it strayed too far from Ū for the normalisation.
void judge_supply(const std::vector<MotorCurveSample>& samples,
                  const MotorCurveFitSettings& settings, MotorCurveFit& fit) {
  std::vector<double> supply;
  for (const MotorCurveSample& s : samples) supply.push_back(s.supply_v);
  fit.mean_supply_v = mean(supply);
  const auto [min_u, max_u] = std::minmax_element(supply.begin(), supply.end());
  if (std::abs(*min_u - settings.nominal_supply_v) > settings.max_supply_deviation_v ||
      std::abs(*max_u - settings.nominal_supply_v) > settings.max_supply_deviation_v) {
    fit.problems.push_back("the supply ranged over " + fixed(*min_u, 2) + " … " + fixed(*max_u, 2) +
                           " V, more than " + fixed(settings.max_supply_deviation_v, 1) +
                           " V from Ū = " + fixed(settings.nominal_supply_v, 1) +
                           " V: set the laboratory supply to Ū (the normalisation by Ū/U holds "
                           "only near it)");
  }
}

// W_i on the way up and down at every grid duty (d > 0) and the scatter about the local lines;
// false (with a problem) when a grid duty has too few samples.
bool fit_grid(const std::vector<MotorCurveSample>& samples, const MotorCurveFitSettings& settings,
              std::size_t wheels, MotorCurveFit& fit) {
  const std::size_t grid_size = settings.duty_grid.size();
  fit.wheel_speed_radps.assign(wheels, std::vector<double>(grid_size, 0.0));
  fit.rising_radps.assign(grid_size, 0.0);
  fit.falling_radps.assign(grid_size, 0.0);
  std::vector<double> all_residuals;
  std::string thin;
  for (std::size_t g = 1; g < grid_size; ++g) {
    const double duty = settings.duty_grid[g];
    for (std::size_t w = 0; w < wheels; ++w) {
      const WindowFit up = fit_window(samples, w, duty, true, settings);
      const WindowFit down = fit_window(samples, w, duty, false, settings);
      if (!up.ok || !down.ok) {
        if (w == 0) {
          thin += (thin.empty() ? "" : ", ") + ("d = " + fixed(duty, 2) + " (" +
                                                std::to_string(up.count) + " up, " +
                                                std::to_string(down.count) + " down)");
        }
        continue;
      }
      fit.wheel_speed_radps[w][g] = 0.5 * (up.value + down.value);
      fit.rising_radps[g] += up.value / static_cast<double>(wheels);
      fit.falling_radps[g] += down.value / static_cast<double>(wheels);
      fit.max_hysteresis_radps = std::max(fit.max_hysteresis_radps, std::abs(up.value - down.value));
      all_residuals.insert(all_residuals.end(), up.residuals.begin(), up.residuals.end());
      all_residuals.insert(all_residuals.end(), down.residuals.begin(), down.residuals.end());
    }
  }
  if (!thin.empty()) {
    fit.problems.push_back("too few samples near " + thin + " (need " +
                           std::to_string(settings.min_window_samples) +
                           " each way within ±" + fixed(settings.window_duty, 2) +
                           "): the sweep is too short or does not cover 0 … 1");
    return false;
  }
  if (!all_residuals.empty()) {
    double sum = 0.0;
    for (const double r : all_residuals) sum += r * r;
    fit.rms_residual_radps = std::sqrt(sum / static_cast<double>(all_residuals.size()));
  }
  return true;
}

// W: the mean over the wheels, and how far the wheels spread about it (d ≥ 0.3).
void mean_curve(const MotorCurveFitSettings& settings, std::size_t wheels, MotorCurveFit& fit) {
  const std::size_t grid_size = settings.duty_grid.size();
  std::vector<double>& speed = fit.curve.no_load_speed_radps;
  speed.assign(grid_size, 0.0);
  for (std::size_t g = 1; g < grid_size; ++g) {
    for (std::size_t w = 0; w < wheels; ++w) {
      speed[g] += fit.wheel_speed_radps[w][g] / static_cast<double>(wheels);
    }
    if (settings.duty_grid[g] >= 0.3 && speed[g] > 0.0) {
      for (std::size_t w = 0; w < wheels; ++w) {
        fit.max_wheel_spread =
            std::max(fit.max_wheel_spread, std::abs(fit.wheel_speed_radps[w][g] / speed[g] - 1.0));
      }
    }
  }
}

// A dead zone wider than the first grid step leaves W ≈ 0 there: keep the table invertible
// with a tiny rise and say so. Anywhere else W must increase by more than the noise.
void judge_rise(const MotorCurveFitSettings& settings, MotorCurveFit& fit) {
  std::vector<double>& speed = fit.curve.no_load_speed_radps;
  for (std::size_t g = 1; g < settings.duty_grid.size(); ++g) {
    const bool in_dead_zone = speed[g] < settings.dead_zone_speed_radps;
    const bool all_below = std::all_of(speed.begin() + 1, speed.begin() + g + 1, [&](double v) {
      return v < settings.dead_zone_speed_radps;
    });
    if (in_dead_zone && all_below) {
      const double floor = 1e-3 * static_cast<double>(g);
      fit.notes.push_back("W(" + fixed(settings.duty_grid[g], 2) + ") = " + fixed(speed[g], 4) +
                          " rad/s lies in the dead zone; tabulated as " + fixed(floor, 3) +
                          " rad/s to keep W invertible");
      speed[g] = floor;
      continue;
    }
    if (!(speed[g] > speed[g - 1])) {
      fit.problems.push_back("W is not increasing: W(" + fixed(settings.duty_grid[g], 2) + ") = " +
                             fixed(speed[g]) + " rad/s ≤ W(" + fixed(settings.duty_grid[g - 1], 2) +
                             ") = " + fixed(speed[g - 1]) +
                             " rad/s (a wheel blocked or slipping, or noisy data)");
    }
  }
}

}  // namespace

MotorCurveFit fit_motor_curve(const std::vector<MotorCurveSample>& samples,
                              const MotorCurveFitSettings& settings) {
  check_settings(samples, settings);
  MotorCurveFit fit;
  fit.samples = samples.size();
  fit.curve.icr = settings.icr;
  fit.curve.duty = settings.duty_grid;
  if (samples.empty() || samples.front().velocity_radps.empty()) {
    fit.problems.push_back("no samples of any wheel: nothing to fit");
    return fit;
  }
  const std::size_t wheels = samples.front().velocity_radps.size();
  judge_supply(samples, settings, fit);
  if (!fit_grid(samples, settings, wheels, fit)) return fit;
  mean_curve(settings, wheels, fit);
  if (fit.rms_residual_radps > settings.max_residual_radps) {
    fit.problems.push_back("the measured speed scatters by " + fixed(fit.rms_residual_radps) +
                           " rad/s (rms) about the local lines, more than " +
                           fixed(settings.max_residual_radps) +
                           " rad/s: the data is too noisy (encoder connections? a wheel touching "
                           "something?)");
  }
  if (fit.max_hysteresis_radps > settings.max_hysteresis_radps) {
    fit.problems.push_back("the sweeps up and down differ by up to " +
                           fixed(fit.max_hysteresis_radps) + " rad/s (limit " +
                           fixed(settings.max_hysteresis_radps) +
                           "): the sweep is too fast for the motor's response; sweep more slowly "
                           "(a longer --duration)");
  }
  judge_rise(settings, fit);
  return fit;
}

}  // namespace marsokhod::calibration
