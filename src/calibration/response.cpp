// Procedure 4.8: the chirp on the stand and the run that fits δ of (4.4) to it (response.hpp).
#include "calibration/response.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include "calibration/procedures.hpp"
#include "core/adaptation/motor_curve.hpp"
#include "core/adaptation/no_load_estimator.hpp"
#include "core/adaptation/no_load_velocity.hpp"

namespace marsokhod::calibration {

double Chirp::frequency_hz(double t_s) const {
  return start_hz + (end_hz - start_hz) * t_s / duration_s;
}

double Chirp::operator()(double t_s) const {
  const double phase =
      2.0 * std::numbers::pi * (start_hz * t_s + 0.5 * (end_hz - start_hz) * t_s * t_s / duration_s);
  const double step = 2.0 * std::sin(std::numbers::pi * std::min(frequency_hz(t_s) * period_s, 0.5));
  const double amplitude = step > 0.0 ? std::min(amplitude_radps, max_step_radps / step)
                                      : amplitude_radps;
  return center_radps + amplitude * std::sin(phase);
}

std::vector<double> predict_response(const std::vector<double>& delta,
                                     const std::vector<double>& commanded_radps) {
  std::vector<double> nu(commanded_radps.size(), 0.0);
  if (commanded_radps.empty()) return nu;
  const auto n = static_cast<std::ptrdiff_t>(commanded_radps.size());
  for (std::ptrdiff_t m = 0; m < n; ++m) {
    double sum = 0.0;
    for (std::size_t j = 0; j < delta.size(); ++j) {
      const std::ptrdiff_t k = m - static_cast<std::ptrdiff_t>(j);
      double w_hat = 0.0;
      if (k < 0) {
        w_hat = commanded_radps.front();
      } else if (k < n) {
        w_hat = commanded_radps[static_cast<std::size_t>(k)];
      }
      sum += delta[j] * w_hat;
    }
    nu[static_cast<std::size_t>(m)] = sum;
  }
  return nu;
}

namespace {

constexpr double kLeadIn_s = 2.0;  // from rest up to the chirp's centre, not fitted
constexpr double kCenter_radps = 1.2;

// ν of the configured δ on the chirp: the rms of w − ν over every wheel (into `quality`) and ν
// of the first wheel (empty without a configured table).
std::vector<double> configured_response(const std::vector<ResponseSeries>& series,
                                        const ResponseParams* configured, std::size_t order,
                                        std::map<std::string, double>& quality) {
  if (configured == nullptr || series.empty()) return {};
  std::vector<double> pooled_err;
  for (const ResponseSeries& s : series) {
    const std::vector<double> nu = predict_response(configured->delta, s.commanded_radps);
    for (std::size_t m = order; m < nu.size(); ++m) {
      pooled_err.push_back(s.measured_radps[m] - nu[m]);
    }
  }
  double sum = 0.0;
  for (const double e : pooled_err) sum += e * e;
  if (!pooled_err.empty()) {
    quality["rms_residual_configured_radps"] =
        std::sqrt(sum / static_cast<double>(pooled_err.size()));
  }
  return predict_response(configured->delta, series.front().commanded_radps);
}

// Figure 4.5 left: δ^j at t = −j·h.
Recording delta_recording(const ResponseFit& fit, const ResponseParams* configured, double h) {
  Recording coefficients;
  coefficients.name = "response_delta";
  coefficients.title = "Procedure 4.8: coefficients δ^j (cf. Figure 4.5 left)";
  coefficients.columns = {"j", "time_s", "delta_fitted", "standard_error", "delta_configured"};
  for (std::size_t j = 0; j < fit.delta.size(); ++j) {
    const double nominal =
        configured != nullptr && j < configured->delta.size() ? configured->delta[j] : 0.0;
    coefficients.rows.push_back({static_cast<double>(j), -static_cast<double>(j) * h,
                                 fit.delta[j], fit.standard_error[j], nominal});
  }
  coefficients.gnuplot =
      std::string(kPlotByColumnHeads) +
      "set title 'Procedure 4.8: δ^j against the time −j·h (cf. Figure 4.5 left)'\n"
      "set xlabel 'time [s]'\nset ylabel 'δ'\nset style fill solid 0.6\n"
      "set boxwidth 0.005\nset xrange [*:0.01]\n"
      "plot 'response_delta.csv' using ($2-0.003):3 with boxes title 'fitted', "
      "'' using ($2-0.003):3:4 with yerrorbars lc 'black' pt 0 title 'standard error', "
      "'' using ($2+0.003):5 with boxes fill pattern 4 title 'configured'\n";
  return coefficients;
}

// Figures 4.4 and 4.5 right: the chirp ŵ, the measured w and ν of the first wheel.
Recording chirp_recording(const std::vector<ResponseSeries>& series,
                          const std::vector<double>& times, const std::vector<double>& fitted_nu,
                          const std::vector<double>& configured_nu) {
  Recording run;
  run.name = "response_chirp";
  run.title = "Procedure 4.8: chirp, measured w and ν (cf. Figures 4.4, 4.5 right)";
  run.columns = {"time_s", "w_hat_radps", "w_radps", "nu_radps", "w_minus_nu_radps",
                 "nu_configured_radps"};
  if (!series.empty()) {
    const ResponseSeries& s = series.front();
    for (std::size_t m = 0; m < s.measured_radps.size(); ++m) {
      run.rows.push_back({times[m], s.commanded_radps[m], s.measured_radps[m], fitted_nu[m],
                          s.measured_radps[m] - fitted_nu[m],
                          configured_nu.empty() ? std::nan("") : configured_nu[m]});
    }
  }
  run.gnuplot =
      std::string(kPlotByColumnHeads) +
      "set multiplot layout 2,1\n"
      "set xlabel 'time [s]'\nset ylabel 'rad/s'\n"
      "plot 'response_chirp.csv' using 1:2 with lines, '' using 1:3 with lines, "
      "'' using 1:4 with lines, '' using 1:5 with lines\n"
      "set title 'the last 3 s, with ν of the configured δ (cf. Figure 4.5 right)'\n"
      "set xrange [GPVAL_DATA_X_MAX-3:GPVAL_DATA_X_MAX]\n"
      "plot 'response_chirp.csv' using 1:2 with linespoints, '' using 1:3 with linespoints, "
      "'' using 1:4 with linespoints, '' using 1:6 with lines dt 2\n"
      "unset multiplot\n";
  return run;
}

void add_response_quality(const ResponseFit& fit, double h, ProcedureResult& result) {
  result.quality["rms_residual_radps"] = fit.residuals.rms;
  result.quality["max_abs_residual_radps"] = fit.residuals.max_abs;
  result.quality["delta_sum"] = fit.sum;
  result.quality["excitation"] = fit.excitation;
  double worst_se = 0.0;
  for (const double se : fit.standard_error) worst_se = std::max(worst_se, se);
  result.quality["max_standard_error"] = worst_se;
  result.quality["duration_s"] = fit.duration_s;
  result.quality["rows"] = static_cast<double>(fit.rows);
  result.quality["period_s"] = h;
}

// Procedure 4.8 on the stand: the wheels follow the chirp of Figure 4.4 (after a lead-in from
// rest), and δ is fitted to every wheel's ŵ and w.
class ResponseProcedure final : public Procedure {
 public:
  double default_duration_s() const override { return 120.0; }

  void prepare(const Run& run) override {
    curve_.emplace(adaptation::select_motor_curve(run.params.motor_curves, run.icr));
    // Up to 0.9 of the Nyquist frequency, each step within 80 % of the duty's slew limit
    // (W′ ≈ 3 rad/s per unit duty).
    const double h = run.period_s();
    chirp_.duration_s = run.duration_s;
    chirp_.period_s = h;
    chirp_.end_hz = 0.45 / h;
    chirp_.max_step_radps = 0.8 * run.params.safety.max_duty_step * 3.0;
    chirp_.center_radps = kCenter_radps;
    lead_cycles_ = static_cast<std::size_t>(std::ceil(kLeadIn_s / h));
    series_.assign(wheels_.size(), {});
  }

  std::optional<BenchSetup> setup(const Run& run) const override {
    return stand_for_run(run, " (Procedure 4.8). The wheels will oscillate faster and faster");
  }

  ProcedureResult fit(const Run& run) const override;

 protected:
  std::size_t cycles(const Run& run) const override {
    return lead_cycles_ + static_cast<std::size_t>(std::ceil(run.duration_s / run.period_s()));
  }

  MotorVector wanted(std::size_t k, double supply_v, const Run& run) const override {
    const double target =
        k < lead_cycles_
            ? kCenter_radps * static_cast<double>(k + 1) / static_cast<double>(lead_cycles_)
            : chirp_(static_cast<double>(k - lead_cycles_) * run.period_s());
    MotorVector duty{};
    for (const std::size_t w : wheels_) {
      duty[w] = adaptation::duty_for_no_load_velocity(*curve_, target, run.params.motors.scale[w],
                                                      supply_v, run.params.motors.nominal_supply_v);
    }
    return duty;
  }

  void record(const RunCycle& c, const Run& run) override {
    if (c.k < lead_cycles_) return;
    times_.push_back(c.sample.time_s);
    for (std::size_t i = 0; i < wheels_.size(); ++i) {
      const std::size_t w = wheels_[i];
      series_[i].commanded_radps.push_back(adaptation::no_load_velocity(
          *curve_, c.sample.duty[w], run.params.motors.scale[w], c.supply_sent_v,
          run.params.motors.nominal_supply_v));
      series_[i].measured_radps.push_back(c.sample.velocity_radps[w]);
    }
  }

 private:
  const std::vector<std::size_t> wheels_ = all_wheels();
  std::optional<adaptation::MotorCurve> curve_;
  Chirp chirp_;
  std::size_t lead_cycles_ = 0;
  std::vector<ResponseSeries> series_;
  std::vector<double> times_;
};

ProcedureResult ResponseProcedure::fit(const Run& run) const {
  const double h = run.period_s();
  const int con = run.params.cycle.con;
  ResponseFitSettings settings;
  settings.period_s = h;
  const ResponseFit fit = fit_response(series_, settings);
  ProcedureResult result;
  result.problems = fit.problems;
  toml::table entry;
  entry.insert("period_s", rounded(h, 1e6));
  entry.insert("con", con);
  toml::array delta;
  for (const double d : fit.delta) delta.push_back(rounded(d, 1e4));
  entry.insert("delta", std::move(delta));
  toml::array responses;
  responses.push_back(std::move(entry));
  result.values.insert("response", std::move(responses));

  // The configured δ on the same data, for comparison.
  const ResponseParams* configured = nullptr;
  try {
    configured = &adaptation::select_response(run.params.responses, h, con);
  } catch (const std::invalid_argument&) {
    configured = nullptr;
  }
  const std::vector<double> configured_nu =
      configured_response(series_, configured, settings.order, result.quality);
  const std::vector<double> fitted_nu =
      series_.empty() ? std::vector<double>{}
                      : predict_response(fit.delta, series_.front().commanded_radps);
  add_response_quality(fit, h, result);
  result.notes.push_back("δ for h = " + fixed(h, 4) + " s, con = " + std::to_string(con) +
                         "; ŵ used the configured ζ and W_" + std::to_string(run.icr) +
                         " (calibrate motor-curve and motor-scale first)");
  result.recordings.push_back(delta_recording(fit, configured, h));
  result.recordings.push_back(chirp_recording(series_, times_, fitted_nu, configured_nu));
  return result;
}

}  // namespace

std::unique_ptr<Procedure> response_procedure() { return std::make_unique<ResponseProcedure>(); }

}  // namespace marsokhod::calibration
