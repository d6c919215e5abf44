// Procedures 4.13/4.14 on the stand (load_gain.hpp): the lighter weight on the front-left wheel,
// the wheel held at each duty level until it has turned over twice, at U = 24, 22 and 20 V.
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "calibration/load_gain.hpp"
#include "calibration/procedures.hpp"
#include "calibration/response.hpp"
#include "core/adaptation/motor_curve.hpp"
#include "core/adaptation/no_load_estimator.hpp"
#include "core/adaptation/no_load_velocity.hpp"

namespace marsokhod::calibration {
namespace {

// Procedure 4.14 swept 24, 22, 20 and 16 V; 16 V lies below the onboard computer's brown-out
// (19.5 V, Field Experiment 6.2), which would silence the bus the procedure runs on, so the sweep
// stops at 20 V (docs/decisions.md).
constexpr std::array<double, 3> kSupplyV{24.0, 22.0, 20.0};
constexpr std::size_t kWheel = kFrontLeft;
// At each level: the first second is left out (ν's filter and the wheel settle on the new duty),
// then the wheel turns over twice, or the level ends after 40 s (then the fit says so).
constexpr double kSettleS = 1.0;
constexpr double kRevolutions = 2.0;
constexpr double kMaxLevelS = 40.0;

class LoadGainProcedure final : public Procedure {
 public:
  void prepare(const Run& run) override {
    curve_.emplace(adaptation::select_motor_curve(run.params.motor_curves, run.icr));
  }

  void command(Bench& bench, const Run& run) override {
    response_ = &adaptation::select_response(run.params.responses, run.period_s(), bench.con());
    for (double volts : kSupplyV) {
      BenchSetup setup;
      setup.placement = BenchSetup::Placement::kStand;
      setup.instruction =
          "Procedure 4.14 at " + fixed(volts, 1) + " V: the rover on the stand, all six wheels "
          "free, the weight strapped to the rim of the front-left wheel (peak torque " +
          fixed(settings_.peak_torque_nm, 2) + " N·m), the laboratory supply set to " +
          fixed(volts, 1) + " V. The wheel turns at five speeds in turn";
      setup.supply_v = volts;
      setup.weight_wheel = kWheel;
      setup.weight_peak_torque_nm = settings_.peak_torque_nm;
      bench.arrange(setup);
      bench.start(run.icr, run.params.cycle.con);
      runs_.push_back(measure_at(bench, run));
      bench.stop();
    }
  }

  std::optional<BenchSetup> teardown(const Run& run) const override {
    BenchSetup off = stand_at_nominal_supply(run.params, ".");
    off.instruction = "Take the weight off the front-left wheel and set the laboratory supply "
                      "back to the nominal voltage.";
    return off;
  }

  ProcedureResult fit(const Run& run) const override;

 private:
  LoadGainRun measure_at(Bench& bench, const Run& run) {
    LoadGainRun out;
    out.supply_v = bench.measure_supply_v();
    std::vector<std::size_t> levels;
    std::vector<double> duties, positions, w_hat, measured;
    double supply_v = run.params.motors.nominal_supply_v;
    for (std::size_t k = 0; k < settings_.duty_levels.size(); ++k) {
      MotorVector wanted{};
      wanted[kWheel] = settings_.duty_levels[k];
      const double start_s = bench.time_s();
      std::optional<double> first_position;
      for (;;) {
        const double supply_sent_v = supply_v;
        const BenchSample& s = bench.cycle(wanted);
        if (s.sensors.supply_v > 0.0) supply_v = s.sensors.supply_v;
        const double at_level_s = s.time_s - start_s;
        levels.push_back(at_level_s < kSettleS ? kSkip : k);
        duties.push_back(s.duty[kWheel]);
        positions.push_back(s.position_rad[kWheel]);
        w_hat.push_back(adaptation::no_load_velocity(*curve_, s.duty[kWheel],
                                                     run.params.motors.scale[kWheel],
                                                     supply_sent_v,
                                                     run.params.motors.nominal_supply_v));
        measured.push_back(s.velocity_radps[kWheel]);
        if (at_level_s < kSettleS) continue;
        if (!first_position) first_position = s.position_rad[kWheel];
        const double turned = std::abs(s.position_rad[kWheel] - *first_position);
        if (turned >= kRevolutions * 2.0 * std::numbers::pi || at_level_s >= kMaxLevelS) break;
      }
    }
    // ν of (4.4) over the whole run: the response filter runs on across the level changes.
    const std::vector<double> nu = predict_response(response_->delta, w_hat);
    for (std::size_t m = 0; m < levels.size(); ++m) {
      if (levels[m] == kSkip) continue;
      out.samples.push_back({levels[m], duties[m], positions[m], measured[m] - nu[m]});
    }
    return out;
  }

  static constexpr std::size_t kSkip = static_cast<std::size_t>(-1);
  LoadGainSettings settings_;
  std::optional<adaptation::MotorCurve> curve_;
  const ResponseParams* response_ = nullptr;
  std::vector<LoadGainRun> runs_;
};

// Figure 4.8 (middle and right): B± against d, one column pair per supply voltage and the table.
Recording table_recording(const LoadGainFit& fit) {
  Recording rec;
  rec.name = "load_gain";
  rec.title = "Procedure 4.14: B+ and B- against the duty at each supply voltage (cf. Figure 4.8)";
  rec.columns = {"duty", "table_same_sign_radps_per_nm", "table_opposite_sign_radps_per_nm"};
  for (double volts : fit.supply_v) {
    rec.columns.push_back("same_sign_at_" + fixed(volts, 1) + "V");
    rec.columns.push_back("opposite_sign_at_" + fixed(volts, 1) + "V");
  }
  for (std::size_t k = 0; k < fit.duty.size(); ++k) {
    std::vector<double> row{fit.duty[k], fit.same_sign_radps_per_nm[k],
                            fit.opposite_sign_radps_per_nm[k]};
    for (const std::vector<LoadGainPoint>& run : fit.points) {
      row.push_back(run[k].same_sign_radps_per_nm);
      row.push_back(run[k].opposite_sign_radps_per_nm);
    }
    rec.rows.push_back(std::move(row));
  }
  rec.gnuplot = std::string(kPlotByColumnHeads) +
                "set xlabel 'd'\nset ylabel 'rad/(s N m)'\nset yrange [0:*]\n"
                "plot for [c=4:*] 'load_gain.csv' using 1:c with points pt 7, "
                "'' using 1:2 with lines lw 2 title 'B+ (table)', "
                "'' using 1:3 with lines lw 2 title 'B- (table)'\n";
  return rec;
}

ProcedureResult LoadGainProcedure::fit(const Run& run) const {
  const LoadGainFit fit = fit_load_gain(runs_, settings_);
  ProcedureResult result;
  result.problems = fit.problems;
  result.quality["max_voltage_spread"] = fit.max_relative_spread;
  result.quality["phase_rad"] = fit.phase_rad;
  result.quality["peak_torque_nm"] = settings_.peak_torque_nm;
  double worst_rms = 0.0;
  for (const Residuals& r : fit.residuals) worst_rms = std::max(worst_rms, r.rms);
  result.quality["max_rms_residual_radps"] = worst_rms;
  if (!fit.problems.empty()) return result;
  toml::table entry;
  entry.insert("icr", run.icr);
  toml::array duty, same, opposite;
  for (std::size_t k = 0; k < fit.duty.size(); ++k) {
    duty.push_back(fit.duty[k]);
    same.push_back(rounded(fit.same_sign_radps_per_nm[k], 1e5));
    opposite.push_back(rounded(fit.opposite_sign_radps_per_nm[k], 1e5));
  }
  entry.insert("duty", std::move(duty));
  entry.insert("same_sign_radps_per_nm", std::move(same));
  entry.insert("opposite_sign_radps_per_nm", std::move(opposite));
  toml::array tables;
  tables.push_back(std::move(entry));
  result.values.insert("load_gain", std::move(tables));
  result.notes.push_back(
      "B±_" + std::to_string(run.icr) + "(d) at d = " + fixed(fit.duty.front(), 1) + " … " +
      fixed(fit.duty.back(), 1) + ", the mean over " + std::to_string(fit.supply_v.size()) +
      " supply voltages, which differ by at most " + fixed(100.0 * fit.max_relative_spread, 1) +
      " %; the table holds its end values below and above (the weighted wheel turns too slowly "
      "below d = 0.2 to measure)");
  result.recordings.push_back(table_recording(fit));
  return result;
}

}  // namespace

std::unique_ptr<Procedure> load_gain_procedure() { return std::make_unique<LoadGainProcedure>(); }

}  // namespace marsokhod::calibration
