// Procedure 4.13: the weight on the front-left wheel and the fit of B⁺, B⁻ (load.hpp).
#include "calibration/load.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "calibration/procedures.hpp"
#include "calibration/response.hpp"
#include "core/adaptation/motor_curve.hpp"
#include "core/adaptation/no_load_estimator.hpp"
#include "core/adaptation/no_load_velocity.hpp"

namespace marsokhod::calibration {
namespace {

constexpr double kPeakTorqueNm = 5.51;  // Procedure 4.13's weight
constexpr double kMaxDuty = 0.6;

// [1, d, d²] then the load's columns.
std::vector<double> row_of(double duty, std::initializer_list<double> load_columns) {
  std::vector<double> row{1.0, duty, duty * duty};
  row.insert(row.end(), load_columns);
  return row;
}

struct GainFit {
  bool ok = false;
  double same = 0.0;
  double opposite = 0.0;
  Residuals residuals;
};

GainFit fit_gains(const std::vector<const LoadSample*>& samples, double phase, double peak) {
  std::vector<std::vector<double>> rows;
  std::vector<double> y;
  for (const LoadSample* s : samples) {
    const double tau = peak * std::sin(s->position_rad + phase);
    const bool same = tau * s->duty >= 0.0;
    rows.push_back(row_of(s->duty, {same ? tau : 0.0, same ? 0.0 : tau}));
    y.push_back(s->load_radps);
  }
  GainFit out;
  try {
    const LeastSquaresFit ls = fit_least_squares(rows, y);
    out.same = ls.coefficients[3];
    out.opposite = ls.coefficients[4];
    out.residuals = ls.residuals;
    out.ok = true;
  } catch (const std::invalid_argument&) {
    out.ok = false;
  }
  return out;
}

// The samples within [min_duty, max_duty] with finite values, and how far the wheel turned there.
std::vector<const LoadSample*> used_samples(const std::vector<LoadSample>& samples,
                                            const LoadFitSettings& settings, LoadFit& fit) {
  std::vector<const LoadSample*> used;
  double min_p = std::numeric_limits<double>::infinity();
  double max_p = -std::numeric_limits<double>::infinity();
  for (const LoadSample& s : samples) {
    if (s.duty < settings.min_duty || s.duty > settings.max_duty) continue;
    if (!std::isfinite(s.load_radps) || !std::isfinite(s.position_rad)) continue;
    used.push_back(&s);
    min_p = std::min(min_p, s.position_rad);
    max_p = std::max(max_p, s.position_rad);
  }
  fit.samples = used.size();
  fit.revolutions = used.empty() ? 0.0 : (max_p - min_p) / (2.0 * std::numbers::pi);
  return used;
}

// Step 1: the phase from the first harmonic; false (with a problem) when it is not determined.
bool fit_phase(const std::vector<const LoadSample*>& used, LoadFit& fit) {
  std::vector<std::vector<double>> rows;
  std::vector<double> y;
  for (const LoadSample* s : used) {
    rows.push_back(row_of(s->duty, {std::sin(s->position_rad), std::cos(s->position_rad)}));
    y.push_back(s->load_radps);
  }
  LeastSquaresFit harmonic;
  try {
    harmonic = fit_least_squares(rows, y);
  } catch (const std::invalid_argument& e) {
    fit.problems.push_back(std::string("the load is not determined by the data (") + e.what() +
                           ")");
    return false;
  }
  const double a = harmonic.coefficients[3];
  const double b = harmonic.coefficients[4];
  fit.amplitude_radps = std::hypot(a, b);
  fit.phase_rad = std::atan2(b, a);
  return true;
}

// B± per duty bin (Figure 4.8), NaN where a bin does not determine them.
void fit_bins(const std::vector<const LoadSample*>& used, const LoadFitSettings& settings,
              LoadFit& fit) {
  for (std::size_t k = 0; k + 1 < settings.bin_edges.size(); ++k) {
    std::vector<const LoadSample*> bin;
    for (const LoadSample* s : used) {
      if (s->duty >= settings.bin_edges[k] && s->duty < settings.bin_edges[k + 1]) bin.push_back(s);
    }
    const GainFit g = bin.size() > 20 ? fit_gains(bin, fit.phase_rad, settings.peak_torque_nm)
                                      : GainFit{};
    fit.bin_duty.push_back(0.5 * (settings.bin_edges[k] + settings.bin_edges[k + 1]));
    fit.bin_same_sign.push_back(g.ok ? g.same : std::nan(""));
    fit.bin_opposite_sign.push_back(g.ok ? g.opposite : std::nan(""));
  }
}

// The problems of a fit whose B± are determined: noise, no weight, a sign.
void judge_load(const LoadFitSettings& settings, LoadFit& fit) {
  if (fit.residuals.rms > settings.max_residual_radps) {
    fit.problems.push_back("l scatters by " + fixed(fit.residuals.rms) + " rad/s (rms) about τ·B±, "
                           "more than " + fixed(settings.max_residual_radps) +
                           " rad/s: the data is too noisy (a loose weight? the wheel touching "
                           "something?)");
  }
  if (fit.amplitude_radps < settings.min_signal_to_noise * fit.residuals.rms) {
    fit.problems.push_back("the periodic load (" + fixed(fit.amplitude_radps) +
                           " rad/s) hardly stands out of the noise (" + fixed(fit.residuals.rms) +
                           " rad/s rms): is the weight strapped to the wheel? the data is too "
                           "noisy");
  }
  if (!(fit.same_sign_radps_per_nm > 0.0) || !(fit.opposite_sign_radps_per_nm > 0.0)) {
    fit.problems.push_back("B⁺ = " + fixed(fit.same_sign_radps_per_nm, 4) + ", B⁻ = " +
                           fixed(fit.opposite_sign_radps_per_nm, 4) +
                           " rad/(s·N·m): both must be positive");
  }
}

}  // namespace

LoadFit fit_load(const std::vector<LoadSample>& samples, const LoadFitSettings& settings) {
  if (!(settings.peak_torque_nm > 0.0)) {
    throw std::invalid_argument("fit_load: the weight's peak torque must be > 0 N·m");
  }
  LoadFit fit;
  const std::vector<const LoadSample*> used = used_samples(samples, settings, fit);
  if (fit.revolutions < settings.min_revolutions) {
    fit.problems.push_back("the wheel turned " + fixed(fit.revolutions, 1) +
                           " revolutions at d ∈ [" + fixed(settings.min_duty, 2) + ", " +
                           fixed(settings.max_duty, 2) +
                           "], need " + fixed(settings.min_revolutions, 1) +
                           ": the sweep is too short (--duration) or the wheel is blocked");
    return fit;
  }
  if (!fit_phase(used, fit)) return fit;
  // Step 2: B⁺ and B⁻.
  const GainFit gains = fit_gains(used, fit.phase_rad, settings.peak_torque_nm);
  if (!gains.ok) {
    fit.problems.push_back("B⁺ and B⁻ are not determined by the data (the torque never changed "
                           "sign: did the wheel turn?)");
    return fit;
  }
  fit.same_sign_radps_per_nm = gains.same;
  fit.opposite_sign_radps_per_nm = gains.opposite;
  fit.residuals = gains.residuals;
  fit_bins(used, settings, fit);
  judge_load(settings, fit);
  return fit;
}

namespace {

// Figure 4.7 right: l against the phase α, coloured by d.
Recording load_recording(const std::vector<LoadSample>& samples, const LoadFit& fit) {
  Recording rec;
  rec.name = "load";
  rec.title = "Procedure 4.13: l = w - nu against the wheel's phase (cf. Figure 4.7)";
  rec.columns = {"time_s", "duty", "alpha_rad", "load_radps", "torque_nm", "model_radps"};
  for (const LoadSample& s : samples) {
    const double alpha = std::remainder(s.position_rad + fit.phase_rad, 2.0 * std::numbers::pi);
    const double wrapped = alpha < 0.0 ? alpha + 2.0 * std::numbers::pi : alpha;
    const double tau = kPeakTorqueNm * std::sin(wrapped);
    const double model = tau * (tau * s.duty >= 0.0 ? fit.same_sign_radps_per_nm
                                                    : fit.opposite_sign_radps_per_nm);
    rec.rows.push_back({s.time_s, s.duty, wrapped, s.load_radps, tau, model});
  }
  rec.gnuplot =
      std::string(kPlotByColumnHeads) +
      "set xlabel 'alpha [rad]'\nset ylabel 'l [rad/s]'\nset cblabel 'd'\n"
      "plot 'load.csv' using 3:($2 >= 0.3 ? $4 : 1/0):2 with points pt 7 ps 0.3 palette "
      "title 'l (d >= 0.3)', '' using 3:($2 >= 0.3 ? $6 : 1/0) with dots lc 'black' "
      "title 'tau B (fitted)'\n";
  return rec;
}

// Figure 4.8: B± per duty bin.
Recording gains_recording(const LoadFit& fit) {
  Recording gains;
  gains.name = "load_gains";
  gains.title = "Procedure 4.13: B+ and B- against the duty (cf. Figure 4.8)";
  gains.columns = {"duty", "gain_same_sign_radps_per_nm", "gain_opposite_sign_radps_per_nm"};
  for (std::size_t k = 0; k < fit.bin_duty.size(); ++k) {
    gains.rows.push_back({fit.bin_duty[k], fit.bin_same_sign[k], fit.bin_opposite_sign[k]});
  }
  gains.gnuplot =
      std::string(kPlotByColumnHeads) +
      "set xlabel 'd'\nset ylabel 'rad/(s N m)'\nset yrange [0:*]\n"
      "plot 'load_gains.csv' using 1:2 with linespoints, '' using 1:3 with linespoints\n";
  return gains;
}

// Procedure 4.13 on the stand: the weight on the front-left wheel, its duty rising slowly to 0.6.
class LoadProcedure final : public Procedure {
 public:
  double default_duration_s() const override { return 90.0; }

  void prepare(const Run& run) override {
    curve_.emplace(adaptation::select_motor_curve(run.params.motor_curves, run.icr));
  }

  std::optional<BenchSetup> setup(const Run& run) const override {
    BenchSetup setup = stand_for_run(
        run, ", and strap the metallic weight tightly to the rim of the front-left wheel "
             "(Procedure 4.13, Figure 4.7: peak torque " + fixed(kPeakTorqueNm, 2) +
                 " N·m). The wheel will turn slowly faster");
    setup.weight_wheel = kWheel;
    setup.weight_peak_torque_nm = kPeakTorqueNm;
    return setup;
  }

  void command(Bench& bench, const Run& run) override {
    response_ = &adaptation::select_response(run.params.responses, run.period_s(), bench.con());
    Procedure::command(bench, run);
  }

  std::optional<BenchSetup> teardown(const Run& run) const override {
    BenchSetup off = *setup(run);  // the weight comes off again
    off.weight_wheel.reset();
    off.weight_peak_torque_nm = 0.0;
    off.instruction = "Take the weight off the front-left wheel.";
    return off;
  }

  ProcedureResult fit(const Run& run) const override;

 protected:
  std::size_t cycles(const Run& run) const override {
    return static_cast<std::size_t>(std::ceil(run.duration_s / run.period_s()));
  }

  MotorVector wanted(std::size_t k, double, const Run& run) const override {
    MotorVector duty{};
    duty[kWheel] = kMaxDuty * static_cast<double>(k + 1) / static_cast<double>(cycles(run));
    return duty;
  }

  void record(const RunCycle& c, const Run& run) override {
    const BenchSample& s = c.sample;
    times_.push_back(s.time_s);
    duties_.push_back(s.duty[kWheel]);
    positions_.push_back(s.position_rad[kWheel]);
    w_hat_.push_back(adaptation::no_load_velocity(*curve_, s.duty[kWheel],
                                                  run.params.motors.scale[kWheel],
                                                  c.supply_sent_v,
                                                  run.params.motors.nominal_supply_v));
    measured_.push_back(s.velocity_radps[kWheel]);
  }

 private:
  static constexpr std::size_t kWheel = kFrontLeft;
  std::optional<adaptation::MotorCurve> curve_;
  const ResponseParams* response_ = nullptr;
  std::vector<double> times_, duties_, positions_, w_hat_, measured_;
};

ProcedureResult LoadProcedure::fit(const Run& run) const {
  const std::vector<double> nu = predict_response(response_->delta, w_hat_);
  std::vector<LoadSample> samples;
  for (std::size_t m = 0; m < times_.size(); ++m) {
    samples.push_back({times_[m], duties_[m], positions_[m], measured_[m] - nu[m]});
  }
  LoadFitSettings settings;
  settings.peak_torque_nm = kPeakTorqueNm;
  const LoadFit fit = fit_load(samples, settings);
  ProcedureResult result;
  result.problems = fit.problems;
  toml::table load;
  load.insert("gain_same_sign_radps_per_nm", rounded(fit.same_sign_radps_per_nm, 1e5));
  load.insert("gain_opposite_sign_radps_per_nm", rounded(fit.opposite_sign_radps_per_nm, 1e5));
  result.values.insert("load", std::move(load));
  result.quality["rms_residual_radps"] = fit.residuals.rms;
  result.quality["max_abs_residual_radps"] = fit.residuals.max_abs;
  result.quality["first_harmonic_radps"] = fit.amplitude_radps;
  result.quality["phase_rad"] = fit.phase_rad;
  result.quality["revolutions"] = fit.revolutions;
  result.quality["samples"] = static_cast<double>(fit.samples);
  result.quality["peak_torque_nm"] = kPeakTorqueNm;
  result.notes.push_back("B± at icr = " + std::to_string(run.icr) + " from d ∈ [" +
                         fixed(settings.min_duty, 1) + ", " + fixed(settings.max_duty, 1) +
                         "] (4.7)'s constants; per-duty values in the load_gains recording");
  if (run.icr != run.params.cycle.icr) {
    result.notes.push_back("icr " + std::to_string(run.icr) + " is not the configured " +
                           std::to_string(run.params.cycle.icr) +
                           ": the driver's [load] holds one pair, for the icr it drives with");
  }
  result.recordings.push_back(load_recording(samples, fit));
  result.recordings.push_back(gains_recording(fit));
  return result;
}

}  // namespace

std::unique_ptr<Procedure> load_procedure() { return std::make_unique<LoadProcedure>(); }

}  // namespace marsokhod::calibration
