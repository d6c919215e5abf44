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

}  // namespace

LoadFit fit_load(const std::vector<LoadSample>& samples, const LoadFitSettings& settings) {
  if (!(settings.peak_torque_nm > 0.0)) {
    throw std::invalid_argument("fit_load: the weight's peak torque must be > 0 N·m");
  }
  LoadFit fit;
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
  if (fit.revolutions < settings.min_revolutions) {
    fit.problems.push_back("the wheel turned " + fixed(fit.revolutions, 1) +
                           " revolutions at d ∈ [" + fixed(settings.min_duty, 2) + ", " +
                           fixed(settings.max_duty, 2) +
                           "], need " + fixed(settings.min_revolutions, 1) +
                           ": the sweep is too short (--duration) or the wheel is blocked");
    return fit;
  }

  // 1. The phase from the first harmonic.
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
    return fit;
  }
  const double a = harmonic.coefficients[3];
  const double b = harmonic.coefficients[4];
  fit.amplitude_radps = std::hypot(a, b);
  fit.phase_rad = std::atan2(b, a);

  // 2. B⁺ and B⁻.
  const GainFit gains = fit_gains(used, fit.phase_rad, settings.peak_torque_nm);
  if (!gains.ok) {
    fit.problems.push_back("B⁺ and B⁻ are not determined by the data (the torque never changed "
                           "sign: did the wheel turn?)");
    return fit;
  }
  fit.same_sign_radps_per_nm = gains.same;
  fit.opposite_sign_radps_per_nm = gains.opposite;
  fit.residuals = gains.residuals;

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
  return fit;
}

ProcedureResult calibrate_load(Bench& bench, const ProcedureOptions& options) {
  const Params& params = bench.params();
  ProcedureResult result;
  result.procedure = "load";
  result.reference = "Procedure 4.13";
  const double duration_s = duration_of(options, 90.0, result.procedure);
  const int icr = options.icr.value_or(params.cycle.icr);
  const std::size_t wheel = kFrontLeft;
  const adaptation::MotorCurve curve(adaptation::select_motor_curve(params.motor_curves, icr));
  const double nominal_v = params.motors.nominal_supply_v;
  const double zeta = params.motors.scale[wheel];

  BenchSetup setup = stand_at_nominal_supply(
      params, ", and strap the metallic weight tightly to the rim of the front-left wheel "
              "(Procedure 4.13, Figure 4.7: peak torque " + fixed(kPeakTorqueNm, 2) +
                  " N·m). The wheel will turn slowly faster for " + fixed(duration_s, 0) + " s.");
  setup.weight_wheel = wheel;
  setup.weight_peak_torque_nm = kPeakTorqueNm;
  bench.arrange(setup);
  bench.start(icr, params.cycle.con);
  const double h = bench.period_s();
  const ResponseParams& response = adaptation::select_response(params.responses, h, bench.con());

  std::vector<double> times;
  std::vector<double> duties;
  std::vector<double> positions;
  std::vector<double> w_hat;
  std::vector<double> measured;
  double supply_v = nominal_v;
  const auto cycles = static_cast<std::size_t>(std::ceil(duration_s / h));
  for (std::size_t k = 0; k < cycles; ++k) {
    MotorVector wanted{};
    wanted[wheel] = kMaxDuty * static_cast<double>(k + 1) / static_cast<double>(cycles);
    const double supply_sent_v = supply_v;
    const BenchSample& s = bench.cycle(wanted);
    if (s.sensors.supply_v > 0.0) supply_v = s.sensors.supply_v;
    times.push_back(s.time_s);
    duties.push_back(s.duty[wheel]);
    positions.push_back(s.position_rad[wheel]);
    w_hat.push_back(adaptation::no_load_velocity(curve, s.duty[wheel], zeta, supply_sent_v,
                                                 nominal_v));
    measured.push_back(s.velocity_radps[wheel]);
  }
  bench.stop();
  BenchSetup off = setup;  // the weight comes off again
  off.weight_wheel.reset();
  off.weight_peak_torque_nm = 0.0;
  off.instruction = "Take the weight off the front-left wheel.";
  bench.arrange(off);

  const std::vector<double> nu = predict_response(response.delta, w_hat);
  std::vector<LoadSample> samples;
  for (std::size_t m = 0; m < times.size(); ++m) {
    samples.push_back({times[m], duties[m], positions[m], measured[m] - nu[m]});
  }
  LoadFitSettings settings;
  settings.peak_torque_nm = kPeakTorqueNm;
  const LoadFit fit = fit_load(samples, settings);
  result.problems = fit.problems;

  toml::table load;
  load.insert("gain_same_sign_radps_per_nm", std::round(fit.same_sign_radps_per_nm * 1e5) / 1e5);
  load.insert("gain_opposite_sign_radps_per_nm",
              std::round(fit.opposite_sign_radps_per_nm * 1e5) / 1e5);
  result.values.insert("load", std::move(load));
  result.quality["rms_residual_radps"] = fit.residuals.rms;
  result.quality["max_abs_residual_radps"] = fit.residuals.max_abs;
  result.quality["first_harmonic_radps"] = fit.amplitude_radps;
  result.quality["phase_rad"] = fit.phase_rad;
  result.quality["revolutions"] = fit.revolutions;
  result.quality["samples"] = static_cast<double>(fit.samples);
  result.quality["peak_torque_nm"] = kPeakTorqueNm;
  result.notes.push_back("B± at icr = " + std::to_string(icr) + " from d ∈ [" +
                         fixed(settings.min_duty, 1) + ", " + fixed(settings.max_duty, 1) +
                         "] (4.7)'s constants; per-duty values in the load_gains recording");
  if (icr != params.cycle.icr) {
    result.notes.push_back("icr " + std::to_string(icr) + " is not the configured " +
                           std::to_string(params.cycle.icr) +
                           ": the driver's [load] holds one pair, for the icr it drives with");
  }

  // Figure 4.7 right: l against the phase α, coloured by d.
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
      "set termoption noenhanced\nset key autotitle columnhead\n"
      "set xlabel 'alpha [rad]'\nset ylabel 'l [rad/s]'\nset cblabel 'd'\n"
      "plot 'load.csv' using 3:($2 >= 0.3 ? $4 : 1/0):2 with points pt 7 ps 0.3 palette "
      "title 'l (d >= 0.3)', '' using 3:($2 >= 0.3 ? $6 : 1/0) with dots lc 'black' "
      "title 'tau B (fitted)'\n";
  result.recordings.push_back(std::move(rec));

  Recording gains;
  gains.name = "load_gains";
  gains.title = "Procedure 4.13: B+ and B- against the duty (cf. Figure 4.8)";
  gains.columns = {"duty", "gain_same_sign_radps_per_nm", "gain_opposite_sign_radps_per_nm"};
  for (std::size_t k = 0; k < fit.bin_duty.size(); ++k) {
    gains.rows.push_back({fit.bin_duty[k], fit.bin_same_sign[k], fit.bin_opposite_sign[k]});
  }
  gains.gnuplot =
      "set termoption noenhanced\nset key autotitle columnhead\n"
      "set xlabel 'd'\nset ylabel 'rad/(s N m)'\nset yrange [0:*]\n"
      "plot 'load_gains.csv' using 1:2 with linespoints, '' using 1:3 with linespoints\n";
  result.recordings.push_back(std::move(gains));
  return result;
}

}  // namespace marsokhod::calibration
