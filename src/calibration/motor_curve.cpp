// Procedure 4.4: the sweep on the stand and the fit of W_icr(d) (motor_curve.hpp).
#include "calibration/motor_curve.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "calibration/fit.hpp"
#include "calibration/procedures.hpp"

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

}  // namespace

MotorCurveFit fit_motor_curve(const std::vector<MotorCurveSample>& samples,
                              const MotorCurveFitSettings& settings) {
  check_settings(samples, settings);
  MotorCurveFit fit;
  fit.samples = samples.size();
  fit.curve.icr = settings.icr;
  fit.curve.duty = settings.duty_grid;
  const std::size_t grid_size = settings.duty_grid.size();
  if (samples.empty() || samples.front().velocity_radps.empty()) {
    fit.problems.push_back("no samples of any wheel: nothing to fit");
    return fit;
  }
  const std::size_t wheels = samples.front().velocity_radps.size();

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

  fit.wheel_speed_radps.assign(wheels, std::vector<double>(grid_size, 0.0));
  fit.rising_radps.assign(grid_size, 0.0);
  fit.falling_radps.assign(grid_size, 0.0);
  std::vector<double> all_residuals;
  std::vector<std::string> thin;
  for (std::size_t g = 1; g < grid_size; ++g) {
    const double duty = settings.duty_grid[g];
    for (std::size_t w = 0; w < wheels; ++w) {
      const WindowFit up = fit_window(samples, w, duty, true, settings);
      const WindowFit down = fit_window(samples, w, duty, false, settings);
      if (!up.ok || !down.ok) {
        if (w == 0) {
          thin.push_back("d = " + fixed(duty, 2) + " (" + std::to_string(up.count) + " up, " +
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
    std::string list;
    for (const std::string& t : thin) list += (list.empty() ? "" : ", ") + t;
    fit.problems.push_back("too few samples near " + list + " (need " +
                           std::to_string(settings.min_window_samples) +
                           " each way within ±" + fixed(settings.window_duty, 2) +
                           "): the sweep is too short or does not cover 0 … 1");
    return fit;
  }
  if (!all_residuals.empty()) {
    double sum = 0.0;
    for (const double r : all_residuals) sum += r * r;
    fit.rms_residual_radps = std::sqrt(sum / static_cast<double>(all_residuals.size()));
  }

  // W: the mean over the wheels.
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
  // A dead zone wider than the first grid step leaves W ≈ 0 there: keep the table invertible
  // with a tiny rise and say so. Anywhere else W must increase by more than the noise.
  for (std::size_t g = 1; g < grid_size; ++g) {
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
  return fit;
}

ProcedureResult calibrate_motor_curve(Bench& bench, const ProcedureOptions& options) {
  const Params& params = bench.params();
  ProcedureResult result;
  result.procedure = "motor-curve";
  result.reference = "Procedure 4.4";

  const int icr = options.icr.value_or(params.cycle.icr);
  const double duration_s = duration_of(options, 120.0, result.procedure);
  const std::vector<std::size_t> wheels = all_wheels();

  bench.arrange(stand_at_nominal_supply(
      params, " (Procedure 4.4). The wheels will speed up slowly to full speed and back."));
  bench.start(icr, params.cycle.con);

  // Up over ~45 %, hold d = 1 for 1.5 s (the first 0.5 s settle), down over ~45 %.
  constexpr double kTopHold_s = 1.5;
  constexpr double kTopSettle_s = 0.5;
  const double ramp_s = std::max(0.5 * (duration_s - kTopHold_s), bench.period_s());
  std::vector<MotorCurveSample> samples;
  auto take = [&](double duty, SweepPhase phase, bool keep) {
    MotorVector wanted{};
    for (const std::size_t w : wheels) wanted[w] = duty;
    const BenchSample& s = bench.cycle(wanted);
    if (!keep) return;
    MotorCurveSample m;
    m.time_s = s.time_s;
    m.duty = s.duty[wheels.front()];
    m.supply_v = s.sensors.supply_v;
    m.phase = phase;
    for (const std::size_t w : wheels) m.velocity_radps.push_back(s.velocity_radps[w]);
    samples.push_back(std::move(m));
  };
  const double h = bench.period_s();
  const auto ramp_cycles = static_cast<std::size_t>(std::ceil(ramp_s / h));
  for (std::size_t k = 0; k <= ramp_cycles; ++k) {
    take(static_cast<double>(k) / static_cast<double>(ramp_cycles), SweepPhase::kRising, true);
  }
  const auto hold_cycles = static_cast<std::size_t>(std::ceil(kTopHold_s / h));
  for (std::size_t k = 0; k < hold_cycles; ++k) {
    take(1.0, SweepPhase::kTop, static_cast<double>(k) * h >= kTopSettle_s);
  }
  for (std::size_t k = 0; k <= ramp_cycles; ++k) {
    take(1.0 - static_cast<double>(k) / static_cast<double>(ramp_cycles), SweepPhase::kFalling,
         true);
  }
  bench.stop();

  MotorCurveFitSettings settings;
  settings.icr = icr;
  settings.nominal_supply_v = params.motors.nominal_supply_v;
  const MotorCurveFit fit = fit_motor_curve(samples, settings);
  result.problems = fit.problems;
  result.notes = fit.notes;

  toml::table entry;
  entry.insert("icr", fit.curve.icr);
  toml::array duty;
  toml::array speed;
  for (std::size_t g = 0; g < fit.curve.duty.size(); ++g) {
    duty.push_back(fit.curve.duty[g]);
    speed.push_back(g < fit.curve.no_load_speed_radps.size()
                        ? std::round(fit.curve.no_load_speed_radps[g] * 1e4) / 1e4
                        : 0.0);
  }
  entry.insert("duty", std::move(duty));
  entry.insert("no_load_speed_radps", std::move(speed));
  toml::array curves;
  curves.push_back(std::move(entry));
  result.values.insert("motor_curve", std::move(curves));

  result.quality["max_hysteresis_radps"] = fit.max_hysteresis_radps;
  result.quality["rms_residual_radps"] = fit.rms_residual_radps;
  result.quality["max_wheel_spread"] = fit.max_wheel_spread;
  result.quality["mean_supply_v"] = fit.mean_supply_v;
  result.quality["sweep_duration_s"] = 2.0 * ramp_s + kTopHold_s;
  result.quality["samples"] = static_cast<double>(fit.samples);
  result.quality["wheels"] = static_cast<double>(wheels.size());
  result.notes.push_back(
      "W is the mean of the measured wheels' curves; run motor-scale (Procedure 4.5) after "
      "loading this table, so that ζ_i is relative to it");

  // Figure 4.2: the sweep (duty, speeds normalised by Ū/U, U over time), and the table.
  Recording sweep;
  sweep.name = "motor_curve_sweep";
  sweep.title = "Procedure 4.4: pwm sweep on the stand (cf. Figure 4.2)";
  sweep.columns = {"time_s", "duty", "supply_v"};
  for (const std::size_t w : wheels) {
    sweep.columns.push_back(std::string("W_") + kMotorNames[w] + "_radps");
  }
  for (const MotorCurveSample& s : samples) {
    std::vector<double> row{s.time_s, s.duty, s.supply_v};
    for (const double v : s.velocity_radps) {
      row.push_back(s.supply_v > 0.0 ? v * params.motors.nominal_supply_v / s.supply_v : 0.0);
    }
    sweep.rows.push_back(std::move(row));
  }
  std::ostringstream plot;
  plot << "set termoption noenhanced\n"
          "set key autotitle columnhead\n"
          "set multiplot layout 2,1\n"
          "set title 'Procedure 4.4: W_"
       << icr
       << "(d): w U-bar/U of each wheel during the sweep (cf. Figure 4.2)'\n"
          "set xlabel 'duty d'\nset ylabel 'w U-bar/U [rad/s]'\n"
          "plot for [c=4:"
       << 3 + wheels.size()
       << "] 'motor_curve_sweep.csv' using 2:c with lines, "
          "'motor_curve_table.csv' using 1:2 with linespoints lw 2 title 'W (fitted)', "
          "'motor_curve_table.csv' using 1:3 with linespoints dt 2 title 'W (configured)'\n"
          "set title 'the supply U during the sweep'\n"
          "set xlabel 'time [s]'\nset ylabel 'U [V]'\n"
          "plot 'motor_curve_sweep.csv' using 1:3 with lines title 'supply U'\n"
          "unset multiplot\n";
  sweep.gnuplot = plot.str();
  result.recordings.push_back(std::move(sweep));

  Recording table;
  table.name = "motor_curve_table";
  table.title = "Procedure 4.4: W at the duty grid, fitted and configured";
  table.columns = {"duty", "W_fitted_radps", "W_configured_radps", "W_up_radps", "W_down_radps"};
  const MotorCurveParams* configured = nullptr;
  for (const MotorCurveParams& c : params.motor_curves) {
    if (c.icr == icr) configured = &c;
  }
  for (std::size_t g = 0; g < fit.curve.duty.size() && g < fit.curve.no_load_speed_radps.size();
       ++g) {
    double nominal = std::nan("");
    if (configured != nullptr) {
      // The configured table at this duty (piecewise linear).
      const double d = fit.curve.duty[g];
      for (std::size_t j = 1; j < configured->duty.size(); ++j) {
        if (d <= configured->duty[j]) {
          const double t =
              (d - configured->duty[j - 1]) / (configured->duty[j] - configured->duty[j - 1]);
          nominal = configured->no_load_speed_radps[j - 1] +
                    t * (configured->no_load_speed_radps[j] - configured->no_load_speed_radps[j - 1]);
          break;
        }
      }
    }
    table.rows.push_back({fit.curve.duty[g], fit.curve.no_load_speed_radps[g], nominal,
                          fit.rising_radps.empty() ? 0.0 : fit.rising_radps[g],
                          fit.falling_radps.empty() ? 0.0 : fit.falling_radps[g]});
  }
  result.recordings.push_back(std::move(table));
  return result;
}

}  // namespace marsokhod::calibration
