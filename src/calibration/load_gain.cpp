// Procedures 4.13/4.14: the fit of B±_icr(d) per duty level and supply voltage (load_gain.hpp).
#include "calibration/load_gain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "calibration/procedure.hpp"

namespace marsokhod::calibration {
namespace {

constexpr std::size_t kMinSamplesPerLevel = 20;

double torque_at(double peak_nm, double position_rad, double phase_rad) {
  return peak_nm * std::sin(position_rad + phase_rad);
}

// The first harmonic's phase with an offset per (run, level); false when not determined.
bool fit_phase(const std::vector<LoadGainRun>& runs, std::size_t levels, LoadGainFit& fit) {
  const std::size_t offsets = runs.size() * levels;
  std::vector<std::vector<double>> rows;
  std::vector<double> y;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    for (const LoadGainSample& s : runs[r].samples) {
      std::vector<double> row(offsets + 2, 0.0);
      row[r * levels + s.level] = 1.0;
      row[offsets] = std::sin(s.position_rad);
      row[offsets + 1] = std::cos(s.position_rad);
      rows.push_back(std::move(row));
      y.push_back(s.load_radps);
    }
  }
  try {
    const LeastSquaresFit harmonic = fit_least_squares(rows, y);
    fit.phase_rad = std::atan2(harmonic.coefficients[offsets + 1], harmonic.coefficients[offsets]);
    return true;
  } catch (const std::invalid_argument& e) {
    fit.problems.push_back(std::string("the weight's phase is not determined by the data (") +
                           e.what() + "): did the wheel turn at every level?");
    return false;
  }
}

// B± at one level of one run; the model's prediction for its samples goes into `predicted`.
LoadGainPoint fit_point(const std::vector<const LoadGainSample*>& samples, double phase_rad,
                        double peak_nm, std::vector<double>& predicted,
                        std::vector<double>& measured) {
  LoadGainPoint point;
  point.samples = samples.size();
  point.same_sign_radps_per_nm = std::nan("");
  point.opposite_sign_radps_per_nm = std::nan("");
  if (samples.empty()) return point;
  double min_p = std::numeric_limits<double>::infinity();
  double max_p = -min_p;
  std::vector<std::vector<double>> rows;
  std::vector<double> y;
  for (const LoadGainSample* s : samples) {
    min_p = std::min(min_p, s->position_rad);
    max_p = std::max(max_p, s->position_rad);
    const double tau = torque_at(peak_nm, s->position_rad, phase_rad);
    const bool same = tau * s->duty >= 0.0;
    rows.push_back({1.0, same ? tau : 0.0, same ? 0.0 : tau});
    y.push_back(s->load_radps);
  }
  point.revolutions = (max_p - min_p) / (2.0 * std::numbers::pi);
  if (samples.size() < kMinSamplesPerLevel) return point;
  try {
    const LeastSquaresFit ls = fit_least_squares(rows, y);
    point.same_sign_radps_per_nm = ls.coefficients[1];
    point.opposite_sign_radps_per_nm = ls.coefficients[2];
    for (std::size_t m = 0; m < rows.size(); ++m) {
      predicted.push_back(ls.coefficients[0] + ls.coefficients[1] * rows[m][1] +
                          ls.coefficients[2] * rows[m][2]);
      measured.push_back(y[m]);
    }
  } catch (const std::invalid_argument&) {
    // Left NaN: the level did not show both signs of τ.
  }
  return point;
}

void fit_run(const LoadGainRun& run, const LoadGainSettings& settings, LoadGainFit& fit) {
  const std::size_t levels = settings.duty_levels.size();
  std::vector<std::vector<const LoadGainSample*>> by_level(levels);
  for (const LoadGainSample& s : run.samples) by_level[s.level].push_back(&s);
  std::vector<double> predicted, measured;
  std::vector<LoadGainPoint> points;
  for (std::size_t k = 0; k < levels; ++k) {
    points.push_back(fit_point(by_level[k], fit.phase_rad, settings.peak_torque_nm, predicted,
                               measured));
    const LoadGainPoint& p = points.back();
    const std::string where = "at d = " + fixed(settings.duty_levels[k], 2) + ", " +
                              fixed(run.supply_v, 1) + " V";
    if (p.revolutions < settings.min_revolutions) {
      fit.problems.push_back("the wheel turned " + fixed(p.revolutions, 1) + " revolutions " +
                             where + ", need " + fixed(settings.min_revolutions, 1) +
                             " (is it blocked, or the weight too heavy for this duty?)");
    } else if (!std::isfinite(p.same_sign_radps_per_nm) ||
               !std::isfinite(p.opposite_sign_radps_per_nm)) {
      fit.problems.push_back("B± are not determined " + where);
    } else if (!(p.same_sign_radps_per_nm > 0.0) || !(p.opposite_sign_radps_per_nm > 0.0)) {
      fit.problems.push_back("B⁺ = " + fixed(p.same_sign_radps_per_nm, 4) + ", B⁻ = " +
                             fixed(p.opposite_sign_radps_per_nm, 4) + " rad/(s·N·m) " + where +
                             ": both must be positive (is the weight strapped to the wheel?)");
    }
  }
  const Residuals residuals = measured.empty() ? Residuals{} : residuals_of(predicted, measured);
  if (residuals.rms > settings.max_residual_radps) {
    fit.problems.push_back("l scatters by " + fixed(residuals.rms) + " rad/s (rms) about c + τ·B± at " +
                           fixed(run.supply_v, 1) + " V, more than " +
                           fixed(settings.max_residual_radps) +
                           " rad/s: a loose weight, or the wheel touching something?");
  }
  fit.points.push_back(std::move(points));
  fit.residuals.push_back(residuals);
}

// The table (the mean over the voltages) and Procedure 4.14's check of their spread.
void fit_table(const LoadGainSettings& settings, LoadGainFit& fit) {
  for (std::size_t k = 0; k < settings.duty_levels.size(); ++k) {
    std::vector<double> same, opposite;
    for (const std::vector<LoadGainPoint>& run : fit.points) {
      same.push_back(run[k].same_sign_radps_per_nm);
      opposite.push_back(run[k].opposite_sign_radps_per_nm);
    }
    const double same_mean = mean(same);
    const double opposite_mean = mean(opposite);
    fit.duty.push_back(settings.duty_levels[k]);
    fit.same_sign_radps_per_nm.push_back(same_mean);
    fit.opposite_sign_radps_per_nm.push_back(opposite_mean);
    for (std::size_t r = 0; r < same.size(); ++r) {
      const double spread = std::max(std::abs(same[r] / same_mean - 1.0),
                                     std::abs(opposite[r] / opposite_mean - 1.0));
      fit.max_relative_spread = std::max(fit.max_relative_spread, spread);
      if (spread > settings.max_voltage_spread) {
        fit.problems.push_back(
            "at d = " + fixed(settings.duty_levels[k], 2) + " B± at " + fixed(fit.supply_v[r], 1) +
            " V (" + fixed(same[r], 4) + ", " + fixed(opposite[r], 4) + ") lie " +
            fixed(100.0 * spread, 0) + " % from their mean over the voltages (" +
            fixed(same_mean, 4) + ", " + fixed(opposite_mean, 4) + "), more than " +
            fixed(100.0 * settings.max_voltage_spread, 0) +
            " %: (4.6) would depend on the supply voltage, against Procedure 4.14");
      }
    }
  }
}

}  // namespace

LoadGainFit fit_load_gain(const std::vector<LoadGainRun>& runs, const LoadGainSettings& settings) {
  if (!(settings.peak_torque_nm > 0.0)) {
    throw std::invalid_argument("fit_load_gain: the weight's peak torque must be > 0 N·m");
  }
  if (settings.duty_levels.empty()) {
    throw std::invalid_argument("fit_load_gain: no duty levels");
  }
  for (const LoadGainRun& run : runs) {
    for (const LoadGainSample& s : run.samples) {
      if (s.level >= settings.duty_levels.size()) {
        throw std::invalid_argument("fit_load_gain: a sample's level " + std::to_string(s.level) +
                                    " is out of range");
      }
    }
  }
  LoadGainFit fit;
  if (runs.empty()) {
    fit.problems.push_back("no run: Procedure 4.14 needs the sweep at every supply voltage");
    return fit;
  }
  for (const LoadGainRun& run : runs) fit.supply_v.push_back(run.supply_v);
  if (!fit_phase(runs, settings.duty_levels.size(), fit)) return fit;
  for (const LoadGainRun& run : runs) fit_run(run, settings, fit);
  if (!fit.problems.empty()) return fit;  // a level without B±: no table
  fit_table(settings, fit);
  return fit;
}

}  // namespace marsokhod::calibration
