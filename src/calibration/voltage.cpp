#include "calibration/voltage.hpp"

#include <cmath>

#include "calibration/fit.hpp"
#include "calibration/procedures.hpp"

namespace marsokhod::calibration {
namespace {

// Procedure 3.5: "several supply voltages U ranging from 27 down to 20 V".
constexpr double kVoltages[] = {27.0, 26.0, 25.0, 24.0, 23.0, 22.0, 21.0, 20.0};
constexpr double kHoldS = 2.0;

// The problems of points with few or wandering readings, and of voltages that span too little.
void judge_points(const std::vector<VoltagePoint>& points, const VoltageFitLimits& limits,
                  ProcedureResult& result) {
  double lowest = points.front().measured_v;
  double highest = lowest;
  for (const VoltagePoint& p : points) {
    lowest = std::min(lowest, p.measured_v);
    highest = std::max(highest, p.measured_v);
    if (p.samples < limits.min_samples_per_point) {
      result.problems.push_back("at " + fixed(p.measured_v, 2) + " V only " +
                                std::to_string(p.samples) + " readings (at least " +
                                std::to_string(limits.min_samples_per_point) + ")");
    }
    if (p.vcc_sd_counts > limits.max_point_sd_counts) {
      result.problems.push_back("at " + fixed(p.measured_v, 2) + " V the reading wanders by " +
                                fixed(p.vcc_sd_counts, 1) + " counts (σ; at most " +
                                fixed(limits.max_point_sd_counts, 1) +
                                "): the supply is not steady or the reading is noisy");
    }
  }
  if (highest - lowest < limits.min_span_v) {
    result.problems.push_back("the voltages span only " + fixed(highest - lowest, 2) +
                              " V (at least " + fixed(limits.min_span_v, 1) + " V)");
  }
}

}  // namespace

ProcedureResult fit_voltage(const std::vector<VoltagePoint>& points,
                            const VoltageFitLimits& limits) {
  ProcedureResult result;
  if (points.size() < limits.min_points) {
    result.problems.push_back("only " + std::to_string(points.size()) + " supply voltages; " +
                              "the fit needs at least " + std::to_string(limits.min_points));
    return result;
  }
  std::vector<double> vcc;
  std::vector<double> volts;
  for (const VoltagePoint& p : points) {
    vcc.push_back(p.vcc_mean_counts);
    volts.push_back(p.measured_v);
  }
  judge_points(points, limits, result);
  LineFit fit;
  try {
    fit = fit_line(vcc, volts);
  } catch (const std::invalid_argument& e) {
    result.problems.push_back(std::string("no fit: ") + e.what());
    return result;
  }
  if (!(fit.gain > 0.0)) {
    result.problems.push_back("U falls as vcc rises (gain " + fixed(fit.gain, 5) +
                              " V/count): the reading does not follow the supply");
  }
  if (fit.residuals.max_abs > limits.max_residual_v) {
    result.problems.push_back("a reading lies " + fixed(fit.residuals.max_abs, 3) +
                              " V off the line (at most " + fixed(limits.max_residual_v, 3) +
                              " V): not affine, or the multimeter readings are off");
  }
  toml::table sensors;
  sensors.insert_or_assign("supply_v_per_count", fit.gain);
  sensors.insert_or_assign("supply_offset_v", fit.offset);
  result.values.insert_or_assign("sensors", std::move(sensors));
  // What a calibrated reading may still lie below U: the line's worst residual and one count (a
  // single reading's rounding and noise). The tether's current bound takes U + this.
  toml::table power;
  power.insert_or_assign("supply_reading_error_v", fit.residuals.max_abs + fit.gain);
  result.values.insert_or_assign("power", std::move(power));
  result.quality["points"] = static_cast<double>(points.size());
  result.quality["rms_residual_v"] = fit.residuals.rms;
  result.quality["max_residual_v"] = fit.residuals.max_abs;
  Recording r;
  r.name = "voltage";
  r.title = "Procedure 3.5: supply voltage U against the ADC6 reading vcc";
  r.columns = {"vcc_counts", "measured_v", "fitted_v", "vcc_sd_counts"};
  for (const VoltagePoint& p : points) {
    r.rows.push_back({p.vcc_mean_counts, p.measured_v, fit.gain * p.vcc_mean_counts + fit.offset,
                      p.vcc_sd_counts});
  }
  r.gnuplot = "set xlabel \"vcc [counts]\"\nset ylabel \"U [V]\"\n"
              "plot \"voltage.csv\" using \"vcc_counts\":\"measured_v\" with points pt 7 "
              "title \"multimeter\", \"voltage.csv\" using \"vcc_counts\":\"fitted_v\" with "
              "lines title \"U = " + fixed(fit.gain, 5) + " vcc " +
              (fit.offset < 0 ? "- " : "+ ") + fixed(std::abs(fit.offset), 4) + "\"";
  result.recordings.push_back(std::move(r));
  return result;
}

namespace {

// Procedure 3.5 on the ground: the laboratory supply set to each voltage in turn, the motors off,
// µ8's vcc held and the multimeter read.
class VoltageProcedure final : public Procedure {
 public:
  double default_duration_s() const override {
    return kHoldS * static_cast<double>(std::size(kVoltages));
  }

  void command(Bench& bench, const Run& run) override {
    const double hold_s = run.duration_s / static_cast<double>(std::size(kVoltages));
    for (double volts : kVoltages) {
      BenchSetup setup;
      setup.placement = BenchSetup::Placement::kGround;
      setup.supply_v = volts;
      setup.instruction = "Procedure 3.5 at " + fixed(volts, 1) +
                          " V: the rover on the laboratory supply, motors off, a multimeter at "
                          "the power distribution board";
      bench.arrange(setup);
      std::vector<double> readings;
      for (const BenchSample& s : bench.hold(MotorVector{}, hold_s)) {
        if (s.raw) readings.push_back(s.raw->vcc);
      }
      VoltagePoint p;
      p.measured_v = bench.measure_supply_v();
      p.samples = readings.size();
      if (!readings.empty()) {
        p.vcc_mean_counts = mean(readings);
        p.vcc_sd_counts = standard_deviation(readings);
      }
      points_.push_back(p);
    }
  }

  // Back to the nominal supply, as the other procedures expect.
  std::optional<BenchSetup> teardown(const Run& run) const override {
    BenchSetup nominal;
    nominal.supply_v = run.params.motors.nominal_supply_v;
    nominal.instruction = "Set the laboratory supply back to the nominal voltage";
    return nominal;
  }

  ProcedureResult fit(const Run&) const override { return fit_voltage(points_); }

 private:
  std::vector<VoltagePoint> points_;
};

}  // namespace

std::unique_ptr<Procedure> voltage_procedure() { return std::make_unique<VoltageProcedure>(); }

}  // namespace marsokhod::calibration
