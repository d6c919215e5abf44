#include "calibration/spin.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "calibration/fit.hpp"
#include "calibration/joints.hpp"
#include "calibration/procedures.hpp"
#include "core/mobility/lever_geometry.hpp"

namespace marsokhod::calibration {
namespace {

constexpr double kSpinDuty = 0.8;        // Procedure 5.1's factor
constexpr double kDefaultRampS = 10.0;   // τ from 0 to 1 ("slowly")
constexpr double kNullRestS = 1.0;       // the gyro's null rate, at rest before the spin

// Centered moving average over ±half samples.
std::vector<double> smoothed(const std::vector<double>& values, std::size_t half) {
  std::vector<double> out(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    const std::size_t lo = k >= half ? k - half : 0;
    const std::size_t hi = std::min(values.size() - 1, k + half);
    double sum = 0.0;
    for (std::size_t i = lo; i <= hi; ++i) sum += values[i];
    out[k] = sum / static_cast<double>(hi - lo + 1);
  }
  return out;
}

double ratio_of(const MotorVector& w) {
  return 0.25 * (w[kFrontLeft] - w[kFrontRight] + w[kBackLeft] - w[kBackRight]) /
         (0.5 * (w[kCenterLeft] - w[kCenterRight]));
}

constexpr const char* kGnuplotSweeps = R"gp(set xlabel "tau"
set ylabel "|omega3| [rad/s]"
set cblabel "c [m]"
plot "spin-sweeps.csv" using "tau":"turn_rate_radps":"clearance_m" \
     with points pt 7 ps 0.3 palette title "turning rate"
)gp";

}  // namespace

MotorVector spin_duty(double tau) {
  const double exterior = kSpinDuty * 0.5 * (1.0 + tau);
  const double center = kSpinDuty * (1.0 - tau);
  MotorVector d{};
  d[kFrontLeft] = exterior;
  d[kBackLeft] = exterior;
  d[kCenterLeft] = center;
  d[kFrontRight] = -exterior;
  d[kBackRight] = -exterior;
  d[kCenterRight] = -center;
  return d;
}

double bending_for_clearance(double clearance_m, const GeometryParams& geometry) {
  const double a = geometry.joint_to_exterior_axle_m;
  const double b = geometry.center_axle_to_joint_m;
  const double cosine = (a * a + b * b - clearance_m * clearance_m) / (2.0 * a * b);
  if (!(std::abs(cosine) < 1.0)) {
    throw std::invalid_argument("no joint angle gives an axle distance of " +
                                fixed(clearance_m) + " m (a = " + fixed(a) + ", b = " +
                                fixed(b) + ")");
  }
  return std::acos(cosine);
}

const std::vector<double>& spin_clearances_m() {
  // From just above the contracted base (0.387 m) to just below the extended one (0.540 m).
  static const std::vector<double> clearances{0.395, 0.43, 0.465, 0.50, 0.53};
  return clearances;
}

SpinPoint spin_point(const SpinSweep& sweep, const SpinLimits& limits,
                     std::vector<std::string>& problems) {
  SpinPoint point;
  point.clearance_m = sweep.clearance_m;
  const std::string at = "c = " + fixed(sweep.clearance_m) + " m: ";
  if (sweep.null_spread_radps > limits.max_null_spread_radps) {
    problems.push_back(at + "the gyro read the rover turning (σ = " +
                       fixed(sweep.null_spread_radps) + " rad/s, at most " +
                       fixed(limits.max_null_spread_radps) +
                       ") in the rest before the sweep, where its null rate is taken: let the "
                       "rover settle where it was set down");
  }
  if (sweep.samples.size() < limits.min_samples) {
    problems.push_back(at + "only " + std::to_string(sweep.samples.size()) +
                       " cycles in the sweep (at least " + std::to_string(limits.min_samples) +
                       " with µ8's readings): ramp τ more slowly, and check that the supply "
                       "holds (a laboratory supply's current limit browns the onboard computer "
                       "out; spin on the batteries)");
    return point;
  }
  const double period_s = (sweep.samples.back().time_s - sweep.samples.front().time_s) /
                          static_cast<double>(sweep.samples.size() - 1);
  const auto half = static_cast<std::size_t>(std::lround(0.5 * limits.averaging_s / period_s));
  std::vector<double> rate;
  for (const SpinSample& s : sweep.samples) rate.push_back(std::abs(s.turn_rate_radps));
  rate = smoothed(rate, half);
  std::array<std::vector<double>, kWheelCount> wheel;
  for (std::size_t i = 0; i < kWheelCount; ++i) {
    std::vector<double> w;
    for (const SpinSample& s : sweep.samples) w.push_back(s.velocity_radps[i]);
    wheel[i] = smoothed(w, half);
  }
  const auto peak = static_cast<std::size_t>(
      std::max_element(rate.begin(), rate.end()) - rate.begin());
  MotorVector w{};
  for (std::size_t i = 0; i < kWheelCount; ++i) w[i] = wheel[i][peak];
  point.tau = sweep.samples[peak].tau;
  point.time_s = sweep.samples[peak].time_s;
  point.turn_rate_radps = rate[peak];
  point.ratio = ratio_of(w);
  point.measured = true;
  if (point.turn_rate_radps < limits.min_turn_rate_radps) {
    problems.push_back(at + "the rover hardly turned (|ω3| at most " +
                       fixed(point.turn_rate_radps) + " rad/s, at least " +
                       fixed(limits.min_turn_rate_radps) +
                       "): is it on the ground, are the wheels powered?");
  } else if (point.tau < limits.edge_tau || point.tau > 1.0 - limits.edge_tau) {
    problems.push_back(at + "the turning rate peaked at τ = " + fixed(point.tau, 2) +
                       ", the edge of the sweep: the optimum was not bracketed");
  }
  return point;
}

namespace {

// The measured data for --plot, whether or not the line is accepted.
void add_recordings(ProcedureResult& result, const std::vector<SpinSweep>& sweeps,
                    const std::vector<SpinPoint>& points, const LineFit* line) {
  Recording fitted;
  fitted.name = "spin";
  fitted.title = line ? "Figure 5.4: F-hat(c) at the peak turning rate and F(c) = " +
                            fixed(line->gain, 2) + " c + " + fixed(line->offset, 2)
                      : "Figure 5.4: F-hat(c) at the peak turning rate (no line)";
  fitted.columns = {"clearance_m", "ratio", "fitted_ratio", "tau", "turn_rate_radps"};
  for (const SpinPoint& p : points) {
    fitted.rows.push_back({p.clearance_m, p.ratio,
                           line ? line->gain * p.clearance_m + line->offset : std::nan(""), p.tau,
                           p.turn_rate_radps});
  }
  fitted.gnuplot = "set xlabel \"c [m]\"\nset ylabel \"F\"\n"
                   "plot \"spin.csv\" using \"clearance_m\":\"ratio\" with points pt 7 title "
                   "\"F-hat(c)\", \"\" using \"clearance_m\":\"fitted_ratio\" with lines title "
                   "\"F(c)\"";
  result.recordings.push_back(std::move(fitted));

  Recording sweep_rec;
  sweep_rec.name = "spin-sweeps";
  sweep_rec.title = "Figure 5.3: turning rate while tau ramps, one colour per axle distance";
  sweep_rec.columns = {"clearance_m", "t_s", "tau", "turn_rate_radps", "w0", "w1", "w2", "w3",
                       "w4", "w5"};
  for (const SpinSweep& sweep : sweeps) {
    for (const SpinSample& s : sweep.samples) {
      sweep_rec.rows.push_back({sweep.clearance_m, s.time_s, s.tau, std::abs(s.turn_rate_radps),
                                s.velocity_radps[0], s.velocity_radps[1], s.velocity_radps[2],
                                s.velocity_radps[3], s.velocity_radps[4], s.velocity_radps[5]});
    }
  }
  sweep_rec.gnuplot = kGnuplotSweeps;
  result.recordings.push_back(std::move(sweep_rec));
}

}  // namespace

ProcedureResult fit_spin(const std::vector<SpinSweep>& sweeps, const SpinLimits& limits) {
  ProcedureResult result;
  std::vector<SpinPoint> points;
  for (const SpinSweep& sweep : sweeps) {
    points.push_back(spin_point(sweep, limits, result.problems));
  }
  if (sweeps.size() < limits.min_clearances) {
    result.problems.push_back("only " + std::to_string(sweeps.size()) +
                              " axle distances; the line needs at least " +
                              std::to_string(limits.min_clearances));
  }
  // The line through the F̂, fitted once: reported whatever the checks below decide.
  std::vector<double> c, f;
  for (const SpinPoint& p : points) {
    if (!p.measured) continue;
    c.push_back(p.clearance_m);
    f.push_back(p.ratio);
  }
  std::optional<LineFit> line;
  std::string no_line;
  try {
    line = fit_line(c, f);
  } catch (const std::invalid_argument& e) {
    no_line = e.what();
  }
  // What the rover did, beside the thesis, whether or not the line is written: a refusal on a
  // ground unlike the thesis' still says what F̂ the spin found there.
  for (const SpinPoint& p : points) {
    if (!p.measured) continue;
    result.notes.push_back(
        "c = " + fixed(p.clearance_m) + " m: F̂ = " + fixed(p.ratio) + " at the peak turning rate " +
        fixed(p.turn_rate_radps) + " rad/s (τ = " + fixed(p.tau, 2) + "); the thesis' F(c) = " +
        fixed(kThesisSpinSlopePerM * p.clearance_m + kThesisSpinOffset, 2));
  }
  if (line) {
    result.notes.push_back("the line through F̂: " + fixed(line->gain, 2) + " c " +
                           (line->offset < 0.0 ? "- " : "+ ") + fixed(std::abs(line->offset), 2) +
                           " (rms " + fixed(line->residuals.rms) + "); the thesis': " +
                           fixed(kThesisSpinSlopePerM, 1) + " c + " + fixed(kThesisSpinOffset, 2));
  }
  for (const SpinPoint& p : points) {
    if (p.measured && !(p.ratio > 1.0)) {  // a sweep too short for a peak says so itself
      result.problems.push_back("c = " + fixed(p.clearance_m) + " m: F̂ = " + fixed(p.ratio) +
                                " ≤ 1: the exterior wheels did not run faster than the center "
                                "ones at the peak turning rate");
    }
  }
  if (!result.problems.empty()) {
    add_recordings(result, sweeps, points, nullptr);
    return result;
  }
  if (!line) {
    result.problems.push_back("no line: " + no_line);
    add_recordings(result, sweeps, points, nullptr);
    return result;
  }
  result.quality["clearances"] = static_cast<double>(points.size());
  result.quality["rms_residual"] = line->residuals.rms;
  result.quality["max_residual"] = line->residuals.max_abs;
  result.quality["r_squared"] = line->r_squared;
  if (!(line->gain > 0.0)) {
    result.problems.push_back("F̂ does not grow with c (slope " + fixed(line->gain) +
                              " /m): chapter 5.1 expects a longer base to need faster exterior "
                              "wheels");
  }
  if (line->residuals.rms > limits.max_rms_residual) {
    result.problems.push_back("F̂ scatters about the line by " + fixed(line->residuals.rms) +
                              " (rms; at most " + fixed(limits.max_rms_residual) +
                              "): uneven ground or a joint that moved");
  }
  toml::table spin;
  spin.insert_or_assign("slope_per_m", line->gain);
  spin.insert_or_assign("offset", line->offset);
  result.values.insert_or_assign("spin", std::move(spin));
  add_recordings(result, sweeps, points, &*line);
  return result;
}

SpinSweep run_spin_sweep(Bench& bench, double clearance_m, double ramp_s,
                         const std::function<void(const BenchSample&)>& observe) {
  const double per_count = bench.params().sensors.gyro_radps_per_count;
  std::vector<double> yaw;
  for (const BenchSample& s : bench.hold(MotorVector{}, kNullRestS)) {
    if (observe) observe(s);
    if (s.raw) yaw.push_back(s.raw->yaw);
  }
  const double null_counts = yaw.empty() ? bench.params().sensors.gyro_null_typ_counts : mean(yaw);
  SpinSweep sweep;
  sweep.clearance_m = clearance_m;
  if (!yaw.empty()) sweep.null_spread_radps = per_count * standard_deviation(yaw);
  const auto cycles = static_cast<long>(std::ceil(ramp_s / bench.period_s()));
  const double start_s = bench.time_s();
  for (long k = 0; k <= cycles; ++k) {
    const double tau = static_cast<double>(k) / static_cast<double>(cycles);
    const BenchSample& s = bench.cycle(spin_duty(tau));
    if (observe) observe(s);
    if (!s.raw) continue;
    sweep.samples.push_back({s.time_s - start_s, tau,
                             per_count * (null_counts - static_cast<double>(s.raw->yaw)),
                             s.velocity_radps});
  }
  bench.stop();
  return sweep;
}

namespace {

// Procedure 5.1: the joints initialised on the ground, then at each axle distance the joints set
// on the stand and a spin on the ground; at the end the joints contracted again.
class SpinProcedure final : public Procedure {
 public:
  double default_duration_s() const override { return kDefaultRampS; }

  void command(Bench& bench, const Run& run) override {
    const GeometryParams& geometry = run.params.geometry;
    BenchSetup ground;
    ground.instruction =
        "Procedure 5.1: set the rover on flat ground of one texture with room to spin, joints in "
        "vertical configuration";
    bench.arrange(ground);
    const JointInitialisation init = initialise_joints(bench);
    JointMover mover(bench, init.dragged_rad);
    for (double c : spin_clearances_m()) {
      const double gamma = bending_for_clearance(c, geometry);
      arrange_on_stand(bench, "Procedure 5.1, c = " + fixed(c) +
                                  " m: lift the rover onto the stand (wheels free) so that the "
                                  "joints can be set");
      if (!mover.move_to(bench, -gamma, gamma)) {
        failure_ = "the joints did not reach γ = " + fixed(gamma) + " rad for c = " + fixed(c) +
                   " m: are they initialised (Procedure 4.3) and free to move?";
        return;
      }
      const auto reached = mover.joint_rad();
      const double reached_c =
          0.5 *
          (mobility::axle_clearance_m(mobility::front_joint_bending_rad(reached[0]), geometry) +
           mobility::axle_clearance_m(mobility::rear_joint_bending_rad(reached[1]), geometry));
      BenchSetup down;
      down.placement = BenchSetup::Placement::kGround;
      down.instruction = "Procedure 5.1, c = " + fixed(c) +
                         " m: set the rover down on the flat ground, with room to spin";
      bench.arrange(down);
      sweeps_.push_back(run_spin_sweep(bench, reached_c, run.duration_s));
    }
    // Back to the vertical configuration the procedure started from.
    arrange_on_stand(bench,
                     "Procedure 5.1 done: lift the rover onto the stand to contract the joints");
    const double contracted = mobility::contracted_bending_rad(geometry);
    contracted_ = mover.move_to(bench, -contracted, contracted);
    BenchSetup back;
    back.instruction = "Procedure 5.1 done: set the rover back on the ground";
    bench.arrange(back);
  }

  ProcedureResult fit(const Run&) const override {
    if (!failure_.empty()) {
      ProcedureResult failed;
      failed.problems.push_back(failure_);
      return failed;
    }
    ProcedureResult result = fit_spin(sweeps_);
    if (!contracted_) {
      result.notes.push_back("the joints did not return to the vertical configuration: contract "
                             "them before driving");
    }
    return result;
  }

 private:
  static void arrange_on_stand(Bench& bench, std::string instruction) {
    BenchSetup stand;
    stand.placement = BenchSetup::Placement::kStand;
    stand.instruction = std::move(instruction);
    bench.arrange(stand);
  }

  std::vector<SpinSweep> sweeps_;
  std::string failure_;
  bool contracted_ = true;
};

}  // namespace

std::unique_ptr<Procedure> spin_procedure() { return std::make_unique<SpinProcedure>(); }

}  // namespace marsokhod::calibration
