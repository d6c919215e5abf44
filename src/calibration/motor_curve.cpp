// Procedure 4.4: the sweep on the stand, and the calibration file's curve and plots from its fit
// (motor_curve.hpp).
#include "calibration/motor_curve.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "calibration/fit.hpp"
#include "calibration/procedures.hpp"

namespace marsokhod::calibration {

namespace {

// Up over ~45 %, hold d = 1 for 1.5 s (the first 0.5 s settle), down over ~45 %.
constexpr double kTopHold_s = 1.5;
constexpr double kTopSettle_s = 0.5;

// Figure 4.2: the sweep, the speeds normalised by Ū/U against the duty, and U over time.
Recording sweep_recording(const std::vector<MotorCurveSample>& samples,
                          const std::vector<std::size_t>& wheels, double nominal_supply_v,
                          int icr) {
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
      row.push_back(s.supply_v > 0.0 ? v * nominal_supply_v / s.supply_v : 0.0);
    }
    sweep.rows.push_back(std::move(row));
  }
  std::ostringstream plot;
  plot << kPlotByColumnHeads
       << "set multiplot layout 2,1\n"
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
  return sweep;
}

// The configured table at duty d (piecewise linear); NaN without one.
double configured_speed(const MotorCurveParams* configured, double d) {
  if (configured == nullptr) return std::nan("");
  for (std::size_t j = 1; j < configured->duty.size(); ++j) {
    if (d <= configured->duty[j]) {
      const double t =
          (d - configured->duty[j - 1]) / (configured->duty[j] - configured->duty[j - 1]);
      return configured->no_load_speed_radps[j - 1] +
             t * (configured->no_load_speed_radps[j] - configured->no_load_speed_radps[j - 1]);
    }
  }
  return std::nan("");
}

// W at the duty grid, fitted (also up and down) and configured.
Recording table_recording(const MotorCurveFit& fit, const Params& params, int icr) {
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
    table.rows.push_back({fit.curve.duty[g], fit.curve.no_load_speed_radps[g],
                          configured_speed(configured, fit.curve.duty[g]),
                          fit.rising_radps.empty() ? 0.0 : fit.rising_radps[g],
                          fit.falling_radps.empty() ? 0.0 : fit.falling_radps[g]});
  }
  return table;
}

// [[motor_curve]] with the fitted W.
toml::array curve_values(const MotorCurveFit& fit) {
  toml::table entry;
  entry.insert("icr", fit.curve.icr);
  toml::array duty;
  toml::array speed;
  for (std::size_t g = 0; g < fit.curve.duty.size(); ++g) {
    duty.push_back(fit.curve.duty[g]);
    speed.push_back(g < fit.curve.no_load_speed_radps.size()
                        ? rounded(fit.curve.no_load_speed_radps[g], 1e4)
                        : 0.0);
  }
  entry.insert("duty", std::move(duty));
  entry.insert("no_load_speed_radps", std::move(speed));
  toml::array curves;
  curves.push_back(std::move(entry));
  return curves;
}

// Procedure 4.4 on the stand: every wheel's duty rises from 0 to 1, holds, and falls back.
class MotorCurveProcedure final : public Procedure {
 public:
  double default_duration_s() const override { return 120.0; }

  void prepare(const Run& run) override {
    const double h = run.period_s();
    ramp_s_ = std::max(0.5 * (run.duration_s - kTopHold_s), h);
    ramp_cycles_ = static_cast<std::size_t>(std::ceil(ramp_s_ / h));
    hold_cycles_ = static_cast<std::size_t>(std::ceil(kTopHold_s / h));
  }

  std::optional<BenchSetup> setup(const Run& run) const override {
    return stand_at_nominal_supply(
        run.params, " (Procedure 4.4). The wheels will speed up slowly to full speed and back.");
  }

  ProcedureResult fit(const Run& run) const override;

 protected:
  std::size_t cycles(const Run&) const override { return 2 * (ramp_cycles_ + 1) + hold_cycles_; }

  MotorVector wanted(std::size_t k, double, const Run&) const override {
    const double ramp = static_cast<double>(ramp_cycles_);
    double duty = 1.0;
    if (k <= ramp_cycles_) {
      duty = static_cast<double>(k) / ramp;
    } else if (k > ramp_cycles_ + hold_cycles_) {
      duty = 1.0 - static_cast<double>(k - ramp_cycles_ - hold_cycles_ - 1) / ramp;
    }
    MotorVector out{};
    for (const std::size_t w : wheels_) out[w] = duty;
    return out;
  }

  void record(const RunCycle& c, const Run& run) override {
    SweepPhase phase = SweepPhase::kTop;
    if (c.k <= ramp_cycles_) {
      phase = SweepPhase::kRising;
    } else if (c.k > ramp_cycles_ + hold_cycles_) {
      phase = SweepPhase::kFalling;
    } else if (static_cast<double>(c.k - ramp_cycles_ - 1) * run.period_s() < kTopSettle_s) {
      return;  // the top's first 0.5 s settle
    }
    MotorCurveSample m;
    m.time_s = c.sample.time_s;
    m.duty = c.sample.duty[wheels_.front()];
    m.supply_v = c.sample.sensors.supply_v;
    m.phase = phase;
    for (const std::size_t w : wheels_) m.velocity_radps.push_back(c.sample.velocity_radps[w]);
    samples_.push_back(std::move(m));
  }

 private:
  const std::vector<std::size_t> wheels_ = all_wheels();
  double ramp_s_ = 0.0;
  std::size_t ramp_cycles_ = 0;
  std::size_t hold_cycles_ = 0;
  std::vector<MotorCurveSample> samples_;
};

ProcedureResult MotorCurveProcedure::fit(const Run& run) const {
  MotorCurveFitSettings settings;
  settings.icr = run.icr;
  settings.nominal_supply_v = run.params.motors.nominal_supply_v;
  const MotorCurveFit fit = fit_motor_curve(samples_, settings);
  ProcedureResult result;
  result.problems = fit.problems;
  result.notes = fit.notes;
  result.values.insert("motor_curve", curve_values(fit));
  result.quality["max_hysteresis_radps"] = fit.max_hysteresis_radps;
  result.quality["rms_residual_radps"] = fit.rms_residual_radps;
  result.quality["max_wheel_spread"] = fit.max_wheel_spread;
  result.quality["mean_supply_v"] = fit.mean_supply_v;
  result.quality["sweep_duration_s"] = 2.0 * ramp_s_ + kTopHold_s;
  result.quality["samples"] = static_cast<double>(fit.samples);
  result.quality["wheels"] = static_cast<double>(wheels_.size());
  result.notes.push_back(
      "W is the mean of the measured wheels' curves; run motor-scale (Procedure 4.5) after "
      "loading this table, so that ζ_i is relative to it");
  result.recordings.push_back(
      sweep_recording(samples_, wheels_, run.params.motors.nominal_supply_v, run.icr));
  result.recordings.push_back(table_recording(fit, run.params, run.icr));
  return result;
}

}  // namespace

std::unique_ptr<Procedure> motor_curve_procedure() {
  return std::make_unique<MotorCurveProcedure>();
}

}  // namespace marsokhod::calibration
