#include "calibration/voltage_drop.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

#include "calibration/fit.hpp"
#include "calibration/procedures.hpp"

namespace marsokhod::calibration {
namespace {

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

double sum_abs_duty(const VoltageDropSample& s) {
  double sum = 0.0;
  for (double d : s.duty) sum += std::abs(d);
  return sum;
}

// Σ|d|, Σl² and Ū − U over the trailing window: the loads are averaged before squaring.
struct Averaged {
  std::vector<double> duty_sum, load_sum, drop_v;
};

Averaged averaged_over_window(const std::vector<VoltageDropSample>& samples, double window_s) {
  Averaged out;
  double duty = 0.0, drop = 0.0;
  MotorVector load{};
  std::size_t first = 0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const VoltageDropSample& s = samples[k];
    duty += sum_abs_duty(s);
    drop += s.reference_supply_v - s.supply_v;
    for (std::size_t i = 0; i < kMotorCount; ++i) load[i] += s.load_radps[i];
    while (samples[first].time_s <= s.time_s - window_s) {
      const VoltageDropSample& old = samples[first];
      duty -= sum_abs_duty(old);
      drop -= old.reference_supply_v - old.supply_v;
      for (std::size_t i = 0; i < kMotorCount; ++i) load[i] -= old.load_radps[i];
      ++first;
    }
    const double n = static_cast<double>(k + 1 - first);
    double load_sq = 0.0;
    for (double l : load) load_sq += (l / n) * (l / n);
    out.duty_sum.push_back(duty / n);
    out.load_sum.push_back(load_sq);
    out.drop_v.push_back(drop / n);
  }
  return out;
}

double correlation(const std::vector<double>& x, const std::vector<double>& y) {
  const double mx = mean(x);
  const double my = mean(y);
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (sxx <= 0.0 || syy <= 0.0) return 1.0;
  return sxy / std::sqrt(sxx * syy);
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

// Figure 4.6: Ū (top) and the drop with the model (bottom).
constexpr const char* kGnuplot = R"gp(set datafile separator ","
set key autotitle columnhead
set multiplot layout 2,1 title "Figure 4.6: voltage drop and (4.5)"
set ylabel "V"
plot "voltage-drop.csv" using "t_s":"reference_supply_v" with lines title "U-bar", \
     "" using "t_s":"supply_v" with lines title "U"
set xlabel "t [s]"
set ylabel "U-bar - U [V]"
plot "voltage-drop.csv" using "t_s":"measured_drop_v" with lines title "measured", \
     "" using "t_s":"predicted_drop_v" with lines title "(4.5)"
unset multiplot
)gp";

}  // namespace

std::vector<VoltageDropSample> read_voltage_drop_samples(
    const std::filesystem::path& telemetry_csv) {
  std::ifstream in(telemetry_csv);
  if (!in) {
    throw std::runtime_error(telemetry_csv.string() +
                             ": cannot be read (give --from the --out folder of "
                             "`marsokhod scenario`, which holds telemetry.csv)");
  }
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(telemetry_csv.string() + ": empty file");
  const std::vector<std::string> header = split_csv_line(line);
  std::map<std::string, std::size_t> column;
  for (std::size_t i = 0; i < header.size(); ++i) column[header[i]] = i;
  auto index = [&](const std::string& name) {
    const auto it = column.find(name);
    if (it == column.end()) {
      throw std::runtime_error(telemetry_csv.string() + ": no column " + name +
                               " (not a telemetry.csv of `marsokhod scenario`?)");
    }
    return it->second;
  };
  const std::size_t t_col = index("t_s");
  const std::size_t running_col = index("driver_running");
  const std::size_t u_col = index("supply_v");
  const std::size_t ref_col = index("reference_supply_v");
  std::array<std::size_t, kMotorCount> duty_col{}, load_col{};
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    duty_col[i] = index(std::string(kMotorNames[i]) + "_duty");
    load_col[i] = index(std::string(kMotorNames[i]) + "_load_radps");
  }

  std::vector<VoltageDropSample> samples;
  std::size_t line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    const std::vector<std::string> fields = split_csv_line(line);
    if (fields.size() != header.size()) {
      throw std::runtime_error(telemetry_csv.string() + ":" + std::to_string(line_number) + ": " +
                               std::to_string(fields.size()) + " fields, the header has " +
                               std::to_string(header.size()));
    }
    auto value = [&](std::size_t col) {
      try {
        return std::stod(fields[col]);
      } catch (const std::exception&) {
        throw std::runtime_error(telemetry_csv.string() + ":" + std::to_string(line_number) +
                                 ": " + header[col] + " is not a number");
      }
    };
    VoltageDropSample s;
    s.time_s = value(t_col);
    s.supply_v = value(u_col);
    s.reference_supply_v = value(ref_col);
    // Before µ8 answered (U = 0) or while the computer is down there is no drop to fit.
    if (value(running_col) < 0.5 || s.supply_v <= 1.0 || s.reference_supply_v <= 1.0) continue;
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      s.duty[i] = value(duty_col[i]);
      s.load_radps[i] = value(load_col[i]);
    }
    samples.push_back(s);
  }
  return samples;
}

Residuals voltage_drop_prediction_residuals(const std::vector<VoltageDropSample>& samples,
                                            double duty_drop_v, double load_drop_v_s2_per_rad2) {
  const Averaged averaged = averaged_over_window(samples, kVoltageDropAveraging_s);
  std::vector<double> predicted;
  for (std::size_t k = 0; k < averaged.drop_v.size(); ++k) {
    predicted.push_back(duty_drop_v * averaged.duty_sum[k] +
                        load_drop_v_s2_per_rad2 * averaged.load_sum[k]);
  }
  return residuals_of(predicted, averaged.drop_v);
}

namespace {

// The problems of a recording that does not excite both terms of (4.5) apart.
void judge_excitation(const Averaged& averaged, ProcedureResult& result) {
  const double duty_spread = standard_deviation(averaged.duty_sum);
  const double load_spread = standard_deviation(averaged.load_sum);
  const double corr = correlation(averaged.duty_sum, averaged.load_sum);
  result.quality["duty_sum_spread"] = duty_spread;
  result.quality["load_sum_spread_rad2_per_s2"] = load_spread;
  result.quality["regressor_correlation"] = corr;
  if (duty_spread < kVoltageDropMinDutySpread) {
    result.problems.push_back("the duty cycles hardly vary (σ of Σ|d| = " + number(duty_spread) +
                              ", at least " + number(kVoltageDropMinDutySpread) +
                              "): ξ is not determined; record a drive that starts, stops and "
                              "changes speed");
  }
  if (load_spread < kVoltageDropMinLoadSpread_rad2_per_s2) {
    result.problems.push_back("the loads hardly vary (σ of Σl² = " + number(load_spread) +
                              " rad²/s², at least " +
                              number(kVoltageDropMinLoadSpread_rad2_per_s2) +
                              "): Ξ is not determined; record a drive over obstacles or a spin");
  }
  if (std::abs(corr) > kVoltageDropMaxCorrelation) {
    result.problems.push_back("Σ|d| and Σl² move together (correlation " + number(corr) +
                              ", at most " + number(kVoltageDropMaxCorrelation) +
                              "): ξ and Ξ cannot be told apart in this recording");
  }
}

// ξ, Ξ into the values and the quality, with the problems of a fit that does not fit.
void take_coefficients(const LeastSquaresFit& fit, const std::vector<double>& drop,
                       ProcedureResult& result) {
  const double xi = fit.coefficients[0];
  const double big_xi = fit.coefficients[1];
  const double drop_mean = mean(drop);
  double total = 0.0;
  for (double d : drop) total += (d - drop_mean) * (d - drop_mean);
  const double ss_res = fit.residuals.rms * fit.residuals.rms * static_cast<double>(drop.size());
  const double r_squared = total > 0.0 ? 1.0 - ss_res / total : 0.0;
  toml::table power;
  power.insert_or_assign("duty_drop_v", xi);
  power.insert_or_assign("load_drop_v_s2_per_rad2", big_xi);
  result.values.insert_or_assign("power", std::move(power));
  result.quality["duty_drop_v"] = xi;
  result.quality["load_drop_v_s2_per_rad2"] = big_xi;
  result.quality["rms_residual_v"] = fit.residuals.rms;
  result.quality["max_residual_v"] = fit.residuals.max_abs;
  result.quality["r_squared"] = r_squared;
  result.quality["mean_drop_v"] = drop_mean;
  if (!(xi > 0.0)) {
    result.problems.push_back("ξ = " + number(xi) +
                              " V is not positive: the drop does not grow with the duty cycles");
  }
  if (!(big_xi > 0.0)) {
    result.problems.push_back("Ξ = " + number(big_xi) +
                              " V s²/rad² is not positive: the drop does not grow with the load");
  }
  if (!(r_squared >= kVoltageDropMinRSquared)) {
    result.problems.push_back("(4.5) explains too little of the drop: R² = " + number(r_squared) +
                              ", at least " + number(kVoltageDropMinRSquared) + " (rms residual " +
                              number(fit.residuals.rms) + " V)");
  }
}

// Figure 4.6: Ū, U and the drop, measured and by (4.5).
Recording drop_recording(const std::vector<VoltageDropSample>& samples, const Averaged& averaged,
                         double xi, double big_xi) {
  Recording recording;
  recording.name = "voltage-drop";
  recording.title = "Figure 4.6: U-bar and U-bar - U with (4.5), 1 s averages";
  recording.columns = {"t_s",          "reference_supply_v", "supply_v",     "measured_drop_v",
                       "predicted_drop_v", "sum_abs_duty",   "sum_load_sq_rad2_per_s2"};
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const VoltageDropSample& s = samples[k];
    recording.rows.push_back({s.time_s, s.reference_supply_v, s.supply_v, averaged.drop_v[k],
                              xi * averaged.duty_sum[k] + big_xi * averaged.load_sum[k],
                              averaged.duty_sum[k], averaged.load_sum[k]});
  }
  recording.gnuplot = kGnuplot;
  return recording;
}

}  // namespace

ProcedureResult fit_voltage_drop(const std::vector<VoltageDropSample>& samples) {
  ProcedureResult result;
  result.quality["samples"] = static_cast<double>(samples.size());
  if (samples.size() < kVoltageDropMinSamples) {
    result.problems.push_back("too few cycles: " + std::to_string(samples.size()) +
                              " with a measured supply voltage, at least " +
                              std::to_string(kVoltageDropMinSamples) +
                              " needed (record a longer drive)");
    return result;
  }
  const Averaged averaged = averaged_over_window(samples, kVoltageDropAveraging_s);
  judge_excitation(averaged, result);
  if (!result.problems.empty()) return result;
  std::vector<std::vector<double>> rows;
  for (std::size_t k = 0; k < averaged.drop_v.size(); ++k) {
    rows.push_back({averaged.duty_sum[k], averaged.load_sum[k]});
  }
  LeastSquaresFit fit;
  try {
    fit = fit_least_squares(rows, averaged.drop_v);
  } catch (const std::invalid_argument& e) {
    result.problems.push_back(std::string("the least-squares fit failed: ") + e.what());
    return result;
  }
  take_coefficients(fit, averaged.drop_v, result);
  result.recordings.push_back(
      drop_recording(samples, averaged, fit.coefficients[0], fit.coefficients[1]));
  return result;
}

namespace {

// (4.5) from a recorded drive: no bench, the command reads the recording's telemetry.csv.
class VoltageDropProcedure final : public Procedure {
 public:
  ProcedureResult fit(const Run& run) const override {
    if (!run.options.from) {
      ProcedureResult result;
      result.problems.push_back(
          "no recording: give --from DIR, the --out folder of `marsokhod scenario` (e.g. "
          "power-management-off) or of `marsokhod run --record`");
      return result;
    }
    const std::filesystem::path csv = *run.options.from / "telemetry.csv";
    ProcedureResult result = fit_voltage_drop(read_voltage_drop_samples(csv));
    result.notes.push_back("fitted from " + csv.string());
    return result;
  }
};

}  // namespace

std::unique_ptr<Procedure> voltage_drop_procedure() {
  return std::make_unique<VoltageDropProcedure>();
}

}  // namespace marsokhod::calibration
