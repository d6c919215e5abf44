// Procedure 4.5: ζ_i at d = 0.7 on the stand (motor_scale.hpp).
#include "calibration/motor_scale.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "calibration/fit.hpp"
#include "calibration/procedures.hpp"
#include "core/adaptation/motor_curve.hpp"

namespace marsokhod::calibration {
namespace {

constexpr double kScaleDuty = 0.7;  // Procedure 4.5

// ζ_i of wheel i from the kept samples: the mean ratio, its scatter and drift.
void fit_wheel(const std::vector<const MotorScaleSample*>& kept, const std::vector<double>& minutes,
               const MotorScaleFitSettings& settings, std::size_t i, MotorScaleFit& fit) {
  std::vector<double> ratio;
  ratio.reserve(kept.size());
  for (const MotorScaleSample* s : kept) {
    ratio.push_back(settings.nominal_supply_v / s->supply_v * s->velocity_radps[i] /
                    settings.curve_speed_radps);
  }
  const double zeta = mean(ratio);
  fit.scale[i] = zeta;
  if (!(zeta > 0.0)) {
    fit.problems.push_back(std::string("wheel ") + kMotorNames[i] + " turned at " +
                           fixed(zeta * settings.curve_speed_radps) +
                           " rad/s on average: it must turn forward at d = 0.7 (blocked? "
                           "wired backwards?)");
    return;
  }
  fit.relative_scatter[i] = standard_deviation(ratio) / zeta;
  try {
    fit.drift_per_min[i] = fit_line(minutes, ratio).gain / zeta;
  } catch (const std::invalid_argument&) {
    fit.drift_per_min[i] = 0.0;
  }
  if (fit.relative_scatter[i] > settings.max_relative_scatter) {
    fit.problems.push_back(std::string("wheel ") + kMotorNames[i] + "'s speed scatters by " +
                           fixed(100.0 * fit.relative_scatter[i], 2) + " % (σ), more than " +
                           fixed(100.0 * settings.max_relative_scatter, 2) +
                           " %: the data is too noisy (encoder connection? the wheel touching "
                           "something?)");
  }
}

}  // namespace

MotorScaleFit fit_motor_scale(const std::vector<MotorScaleSample>& samples,
                              const MotorScaleFitSettings& settings) {
  if (!(settings.curve_speed_radps > 0.0) || !(settings.nominal_supply_v > 0.0)) {
    throw std::invalid_argument("fit_motor_scale: W(d) and Ū must be positive");
  }
  MotorScaleFit fit;
  if (samples.empty()) {
    fit.problems.push_back("no samples: nothing to fit");
    return fit;
  }
  const double start_s = samples.front().time_s + settings.settle_s;
  std::vector<const MotorScaleSample*> kept;
  for (const MotorScaleSample& s : samples) {
    if (s.time_s >= start_s) kept.push_back(&s);
  }
  fit.samples = kept.size();
  fit.duration_s = kept.size() < 2 ? 0.0 : kept.back()->time_s - kept.front()->time_s;
  if (kept.size() < 2 || fit.duration_s < settings.min_duration_s) {
    fit.problems.push_back("the run is too short: " + fixed(fit.duration_s, 1) +
                           " s at d = 0.7 after the first " + fixed(settings.settle_s, 1) +
                           " s, need at least " + fixed(settings.min_duration_s, 1) +
                           " s (--duration; the thesis ran 30 min)");
    return fit;
  }
  std::vector<double> supply;
  std::vector<double> minutes;
  for (const MotorScaleSample* s : kept) {
    supply.push_back(s->supply_v);
    minutes.push_back((s->time_s - kept.front()->time_s) / 60.0);
  }
  fit.mean_supply_v = mean(supply);
  const auto [min_u, max_u] = std::minmax_element(supply.begin(), supply.end());
  if (!(*min_u > 0.0) ||
      std::max(std::abs(*min_u - settings.nominal_supply_v),
               std::abs(*max_u - settings.nominal_supply_v)) > settings.max_supply_deviation_v) {
    fit.problems.push_back("the supply ranged over " + fixed(*min_u, 2) + " … " + fixed(*max_u, 2) +
                           " V, more than " + fixed(settings.max_supply_deviation_v, 1) +
                           " V from Ū = " + fixed(settings.nominal_supply_v, 1) +
                           " V: set the laboratory supply to Ū");
    return fit;
  }
  for (std::size_t i = 0; i < kWheelCount; ++i) fit_wheel(kept, minutes, settings, i, fit);
  fit.scale[kFrontJoint] = fit.scale[kFrontRight];  // the shared power cables (Procedure 4.5)
  fit.scale[kRearJoint] = fit.scale[kBackLeft];
  return fit;
}

namespace {

// Figure 4.3: the wheels' speeds normalised by Ū/U over the run.
Recording warmup_recording(const std::vector<MotorScaleSample>& samples, double nominal_supply_v) {
  Recording warmup;
  warmup.name = "motor_scale";
  warmup.title = "Procedure 4.5: wheel speeds at d = 0.7, normalised by U-bar/U (cf. Figure 4.3)";
  warmup.columns = {"time_s", "supply_v"};
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    warmup.columns.push_back(std::string("w_") + kMotorNames[i] + "_radps");
  }
  for (const MotorScaleSample& s : samples) {
    std::vector<double> row{s.time_s, s.supply_v};
    for (std::size_t i = 0; i < kWheelCount; ++i) {
      row.push_back(s.supply_v > 0.0 ? s.velocity_radps[i] * nominal_supply_v / s.supply_v : 0.0);
    }
    warmup.rows.push_back(std::move(row));
  }
  warmup.gnuplot = std::string(kPlotByColumnHeads) +
                   "set xlabel 'time [s]'\nset ylabel 'w U-bar/U [rad/s]'\n"
                   "plot for [c=3:8] 'motor_scale.csv' using 1:c with lines\n";
  return warmup;
}

// Procedure 4.5 on the stand: every wheel held at d = 0.7 for the run.
class MotorScaleProcedure final : public Procedure {
 public:
  double default_duration_s() const override { return 120.0; }

  void prepare(const Run& run) override {
    const adaptation::MotorCurve curve(
        adaptation::select_motor_curve(run.params.motor_curves, run.icr));
    curve_speed_radps_ = curve.velocity_radps(kScaleDuty);
  }

  std::optional<BenchSetup> setup(const Run& run) const override {
    return stand_for_run(run, " (Procedure 4.5). The wheels will turn at d = 0.7");
  }

  ProcedureResult fit(const Run& run) const override;

 protected:
  // As Bench::hold: whole cycles, at least one.
  std::size_t cycles(const Run& run) const override {
    return static_cast<std::size_t>(
        std::max<long>(1, std::lround(run.duration_s / run.period_s())));
  }

  MotorVector wanted(std::size_t, double, const Run&) const override {
    MotorVector duty{};
    for (std::size_t i = 0; i < kWheelCount; ++i) duty[i] = kScaleDuty;
    return duty;
  }

  void record(const RunCycle& c, const Run&) override {
    MotorScaleSample m;
    m.time_s = c.sample.time_s;
    m.supply_v = c.sample.sensors.supply_v;
    for (std::size_t i = 0; i < kWheelCount; ++i) m.velocity_radps[i] = c.sample.velocity_radps[i];
    samples_.push_back(m);
  }

 private:
  double curve_speed_radps_ = 0.0;
  std::vector<MotorScaleSample> samples_;
};

ProcedureResult MotorScaleProcedure::fit(const Run& run) const {
  MotorScaleFitSettings settings;
  settings.nominal_supply_v = run.params.motors.nominal_supply_v;
  settings.curve_speed_radps = curve_speed_radps_;
  const MotorScaleFit fit = fit_motor_scale(samples_, settings);
  ProcedureResult result;
  result.problems = fit.problems;
  toml::array scale;
  for (const double z : fit.scale) scale.push_back(rounded(z, 1e4));
  toml::table motors;
  motors.insert("scale", std::move(scale));
  result.values.insert("motors", std::move(motors));

  double worst_scatter = 0.0;
  double worst_drift = 0.0;
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    worst_scatter = std::max(worst_scatter, fit.relative_scatter[i]);
    worst_drift = std::max(worst_drift, std::abs(fit.drift_per_min[i]));
  }
  result.quality["max_relative_scatter"] = worst_scatter;
  result.quality["max_drift_per_min"] = worst_drift;
  result.quality["duration_s"] = fit.duration_s;
  result.quality["samples"] = static_cast<double>(fit.samples);
  result.quality["mean_supply_v"] = fit.mean_supply_v;
  result.quality["curve_speed_radps"] = curve_speed_radps_;
  result.notes.push_back("ζ_i is relative to the configured W_" + std::to_string(run.icr) +
                         "(0.7) = " + fixed(curve_speed_radps_) +
                         " rad/s; ζ6 = ζ1 and ζ7 = ζ4 (shared power cables)");
  result.recordings.push_back(warmup_recording(samples_, settings.nominal_supply_v));
  return result;
}

}  // namespace

std::unique_ptr<Procedure> motor_scale_procedure() {
  return std::make_unique<MotorScaleProcedure>();
}

}  // namespace marsokhod::calibration
