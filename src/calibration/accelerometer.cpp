#include "calibration/accelerometer.hpp"

#include <cmath>
#include <numbers>
#include <optional>

#include "calibration/fit.hpp"
#include "calibration/procedures.hpp"

namespace marsokhod::calibration {
namespace {

constexpr double kDefaultRestS = 3.0;  // per placement: "a few seconds of rest"

std::string placement_name(std::size_t axis, bool up) {
  return "x" + std::to_string(axis + 1) + (up ? " up" : " down");
}

struct AxisReading {
  double mean_counts = 0.0;
  double sd_counts = 0.0;
};

AxisReading axis_reading(const AccelerometerPlacement& p, std::size_t axis) {
  std::vector<double> values;
  for (const auto& r : p.readings_counts) values.push_back(r[axis]);
  return {mean(values), standard_deviation(values)};
}

constexpr const char* kGnuplot = R"gp(set xlabel "cycle"
set ylabel "acc [counts]"
plot "accelerometer.csv" using 0:"acc1_counts" with points pt 7 ps 0.3 title "acc1", \
     "" using 0:"acc2_counts" with points pt 7 ps 0.3 title "acc2", \
     "" using 0:"acc3_counts" with points pt 7 ps 0.3 title "acc3"
)gp";

}  // namespace

const std::array<StandPose, 6>& accelerometer_poses() {
  // R = Ry(pitch)·Rx(roll) (bench.hpp): roll +π/2 lifts the left side (x2 up), pitch −π/2 lifts
  // the nose (x1 up), roll π turns the rover upside down (x3 down).
  constexpr double kQuarter = std::numbers::pi / 2;
  static const std::array<StandPose, 6> poses{{
      {0, true, 0.0, -kQuarter,
       "Procedure 3.3, x1 up: stand the rover on its rear end, nose pointing straight up, and "
       "let it rest"},
      {0, false, 0.0, kQuarter,
       "Procedure 3.3, x1 down: stand the rover on its nose, rear pointing straight up, and let "
       "it rest"},
      {1, true, kQuarter, 0.0,
       "Procedure 3.3, x2 up: lay the rover on its right side (left side up), level, and let it "
       "rest"},
      {1, false, -kQuarter, 0.0,
       "Procedure 3.3, x2 down: lay the rover on its left side (right side up), level, and let "
       "it rest"},
      {2, true, 0.0, 0.0,
       "Procedure 3.3, x3 up: set the rover upright and level on the stand and let it rest"},
      {2, false, std::numbers::pi, 0.0,
       "Procedure 3.3, x3 down: turn the rover upside down, level, and let it rest"},
  }};
  return poses;
}

namespace {

// table[axis][up ? 1 : 0]: each placement's reading of the axis along gravity.
using GravityTable = std::array<std::array<std::optional<AxisReading>, 2>, 3>;

// The table from the placements, with the problems of placements that are short, not at rest,
// twice or missing.
GravityTable gravity_table(const std::vector<AccelerometerPlacement>& placements,
                           const AccelerometerLimits& limits, ProcedureResult& result) {
  GravityTable table{};
  for (const AccelerometerPlacement& p : placements) {
    const std::string name = placement_name(p.axis, p.axis_up);
    if (p.axis >= 3) {
      result.problems.push_back("a placement names axis " + std::to_string(p.axis + 1) +
                                "; the accelerometer has x1, x2, x3");
      continue;
    }
    if (p.readings_counts.size() < limits.min_samples) {
      result.problems.push_back(name + ": only " + std::to_string(p.readings_counts.size()) +
                                " readings (at least " + std::to_string(limits.min_samples) +
                                "): rest longer");
      continue;
    }
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const AxisReading r = axis_reading(p, axis);
      if (r.sd_counts > limits.max_rest_sd_counts) {
        result.problems.push_back(name + ": acc" + std::to_string(axis + 1) + " wanders by " +
                                  fixed(r.sd_counts, 1) + " counts (σ; at most " +
                                  fixed(limits.max_rest_sd_counts, 1) +
                                  "): the rover is not at rest");
      }
    }
    auto& slot = table[p.axis][p.axis_up ? 1 : 0];
    if (slot) {
      result.problems.push_back(name + " was measured twice");
      continue;
    }
    slot = axis_reading(p, p.axis);
  }
  for (std::size_t axis = 0; axis < 3; ++axis) {
    for (bool up : {true, false}) {
      if (!table[axis][up ? 1 : 0]) {
        result.problems.push_back(placement_name(axis, up) + " is missing (or was refused)");
      }
    }
  }
  return table;
}

// Each axis' span acc(+g) − acc(−g) against the configured one.
void judge_spans(const std::array<double, 3>& minus, const std::array<double, 3>& plus,
                 const SensorParams& configured, const AccelerometerLimits& limits,
                 ProcedureResult& result) {
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const double span = plus[axis] - minus[axis];
    const AccelerometerAxisParams& nominal = configured.accelerometer[axis];
    const double nominal_span = nominal.plus_g_counts - nominal.minus_g_counts;
    const double ratio = nominal_span != 0.0 ? span / nominal_span : 0.0;
    const std::string acc = "acc" + std::to_string(axis + 1);
    result.quality[acc + "_span_counts"] = span;
    if (!(ratio >= limits.min_span_ratio && ratio <= limits.max_span_ratio)) {
      result.problems.push_back(
          acc + ": up and down differ by " + fixed(span, 1) + " counts, the configured table by " +
          fixed(nominal_span, 1) + " (allowed " + fixed(limits.min_span_ratio, 2) + "–" +
          fixed(limits.max_span_ratio, 2) +
          " times that, same sign): a placement was wrong or the axis does not respond");
    }
  }
}

// Across gravity an axis reads its mid value: checks that each placement was the one asked for.
void judge_cross_axes(const std::vector<AccelerometerPlacement>& placements,
                      const std::array<double, 3>& minus, const std::array<double, 3>& plus,
                      const AccelerometerLimits& limits, ProcedureResult& result) {
  double worst_cross = 0.0;
  for (const AccelerometerPlacement& p : placements) {
    for (std::size_t axis = 0; axis < 3; ++axis) {
      if (axis == p.axis) continue;
      const double span = plus[axis] - minus[axis];
      const double mid = 0.5 * (plus[axis] + minus[axis]);
      const double off = span != 0.0 ? std::abs(axis_reading(p, axis).mean_counts - mid) /
                                           std::abs(span)
                                     : 1.0;
      worst_cross = std::max(worst_cross, off);
      if (off > limits.max_cross_axis_fraction) {
        result.problems.push_back(placement_name(p.axis, p.axis_up) + ": acc" +
                                  std::to_string(axis + 1) + " is " + fixed(off * 100.0, 0) +
                                  " % of its span away from level (at most " +
                                  fixed(limits.max_cross_axis_fraction * 100.0, 0) +
                                  " %): the rover was not turned as asked");
      }
    }
  }
  result.quality["max_cross_axis_fraction"] = worst_cross;
}

// Every reading of every placement, for the plot.
Recording readings_recording(const std::vector<AccelerometerPlacement>& placements) {
  Recording r;
  r.name = "accelerometer";
  r.title = "Procedure 3.3: acc at rest in the six placements";
  r.columns = {"placement", "axis", "axis_up", "acc1_counts", "acc2_counts", "acc3_counts"};
  for (std::size_t k = 0; k < placements.size(); ++k) {
    const AccelerometerPlacement& p = placements[k];
    for (const auto& reading : p.readings_counts) {
      r.rows.push_back({static_cast<double>(k), static_cast<double>(p.axis + 1),
                        p.axis_up ? 1.0 : 0.0, reading[0], reading[1], reading[2]});
    }
  }
  r.gnuplot = kGnuplot;
  return r;
}

}  // namespace

ProcedureResult fit_accelerometer(const std::vector<AccelerometerPlacement>& placements,
                                  const SensorParams& configured,
                                  const AccelerometerLimits& limits) {
  ProcedureResult result;
  const GravityTable table = gravity_table(placements, limits, result);
  if (!result.problems.empty()) return result;

  std::array<double, 3> minus{}, plus{};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    plus[axis] = table[axis][1]->mean_counts;
    minus[axis] = table[axis][0]->mean_counts;
  }
  judge_spans(minus, plus, configured, limits, result);
  judge_cross_axes(placements, minus, plus, limits, result);
  double worst_sd = 0.0;
  for (const auto& axis : table) {
    for (const auto& entry : axis) worst_sd = std::max(worst_sd, entry->sd_counts);
  }
  result.quality["max_rest_sd_counts"] = worst_sd;

  toml::array minus_array, plus_array;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    minus_array.push_back(minus[axis]);
    plus_array.push_back(plus[axis]);
  }
  toml::table sensors;
  sensors.insert_or_assign("accelerometer_minus_g_counts", std::move(minus_array));
  sensors.insert_or_assign("accelerometer_plus_g_counts", std::move(plus_array));
  result.values.insert_or_assign("sensors", std::move(sensors));
  result.recordings.push_back(readings_recording(placements));
  return result;
}

namespace {

// Procedure 3.3 on the stand: the rover turned into each of the six poses in turn, at rest.
class AccelerometerProcedure final : public Procedure {
 public:
  double default_duration_s() const override { return kDefaultRestS * 6.0; }

  void command(Bench& bench, const Run& run) override {
    const double rest_s = run.duration_s / 6.0;
    for (const StandPose& pose : accelerometer_poses()) {
      BenchSetup setup;
      setup.placement = BenchSetup::Placement::kStand;
      setup.stand_roll_rad = pose.roll_rad;
      setup.stand_pitch_rad = pose.pitch_rad;
      setup.instruction = pose.instruction;
      bench.arrange(setup);
      AccelerometerPlacement p;
      p.axis = pose.axis;
      p.axis_up = pose.axis_up;
      for (const BenchSample& s : bench.hold(MotorVector{}, rest_s)) {
        if (!s.raw) continue;
        p.readings_counts.push_back({static_cast<double>(s.raw->acc[0]),
                                     static_cast<double>(s.raw->acc[1]),
                                     static_cast<double>(s.raw->acc[2])});
      }
      placements_.push_back(std::move(p));
    }
  }

  std::optional<BenchSetup> teardown(const Run&) const override {
    BenchSetup ground;
    ground.instruction = "Procedure 3.3 done: set the rover back on its wheels";
    return ground;
  }

  ProcedureResult fit(const Run& run) const override {
    return fit_accelerometer(placements_, run.params.sensors);
  }

 private:
  std::vector<AccelerometerPlacement> placements_;
};

}  // namespace

std::unique_ptr<Procedure> accelerometer_procedure() {
  return std::make_unique<AccelerometerProcedure>();
}

}  // namespace marsokhod::calibration
