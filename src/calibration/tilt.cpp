#include "calibration/tilt.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "calibration/fit.hpp"
#include "calibration/procedures.hpp"

namespace marsokhod::calibration {
namespace {

constexpr double kDefaultRestS = 3.0;  // per placement
// The hand turns the axles past ±30°, so they rest on their stops.
constexpr double kBeyondStopRad = kTiltStopRad + 0.2;

struct TiltPose {
  double tilt_rad;
  const char* name;
  const char* instruction;
};

constexpr std::array<TiltPose, 4> kPoses{{
    {kBeyondStopRad, "+30° stop",
     "Procedure 3.4, 1 of 4: on the stand, turn the front and the rear axle (left wheels up) "
     "against their stops at +30° relative to the center axle and hold them there"},
    {0.0, "level from above",
     "Procedure 3.4, 2 of 4: let both axles down from that stop until they are parallel to the "
     "center axle, and hold them there"},
    {-kBeyondStopRad, "−30° stop",
     "Procedure 3.4, 3 of 4: turn both axles on down (left wheels down) against their stops at "
     "−30° and hold them there"},
    {0.0, "level from below",
     "Procedure 3.4, 4 of 4: bring both axles up from that stop until they are parallel to the "
     "center axle again, and hold them there"},
}};

struct ChannelMeans {
  std::array<double, 4> means{};
  double worst_sd = 0.0;
};

// The four means of one channel, with the problems of short or unsteady placements.
ChannelMeans channel_means(const TiltPlacements& placements, bool front, const TiltLimits& limits,
                           ProcedureResult& result) {
  ChannelMeans out;
  const std::string channel = front ? "tltᶠ" : "tltʳ";
  for (std::size_t k = 0; k < placements.size(); ++k) {
    const std::vector<double>& counts =
        front ? placements[k].front_counts : placements[k].rear_counts;
    const std::string where = channel + " at " + kPoses[k].name;
    if (counts.size() < limits.min_samples) {
      result.problems.push_back(where + ": " + std::to_string(counts.size()) +
                                " readings, need at least " + std::to_string(limits.min_samples) +
                                " (hold the axles longer: --duration)");
      continue;
    }
    out.means[k] = mean(counts);
    const double sd = standard_deviation(counts);
    out.worst_sd = std::max(out.worst_sd, sd);
    if (sd > limits.max_rest_sd_counts) {
      result.problems.push_back(where + ": the readings scatter by " + fixed(sd, 2) +
                                " counts (at most " + fixed(limits.max_rest_sd_counts, 1) +
                                "); hold the axles still");
    }
  }
  return out;
}

void judge(const TiltFit& fit, double configured_gain, const std::string& name,
           const TiltLimits& limits, ProcedureResult& result) {
  const double ratio = fit.gain_rad_per_count / configured_gain;
  if (!(ratio >= limits.min_gain_ratio && ratio <= limits.max_gain_ratio)) {
    result.problems.push_back(name + ": gain " + fixed(fit.gain_rad_per_count, 5) +
                              " rad/count is " + fixed(ratio, 2) + " times the configured " +
                              fixed(configured_gain, 5) + " (allowed " +
                              fixed(limits.min_gain_ratio, 1) + "–" +
                              fixed(limits.max_gain_ratio, 1) +
                              "): a placement was wrong or the potentiometer is loose");
  }
  if (std::abs(fit.span_mismatch_counts) > limits.max_span_mismatch_counts) {
    result.problems.push_back(name + ": the stops' spans differ by " +
                              fixed(fit.span_mismatch_counts, 1) + " counts (at most " +
                              fixed(limits.max_span_mismatch_counts, 1) +
                              "): an axle missed its stop or was not level");
  }
  if (!(fit.play_rad >= 0.0 && fit.play_rad <= limits.max_play_rad)) {
    result.problems.push_back(name + ": a play of " + fixed(fit.play_rad, 3) +
                              " rad is not plausible (0 to " + fixed(limits.max_play_rad, 2) +
                              "): the placements were not in the procedure's order");
  }
}

constexpr const char* kGnuplot = R"gp(set xlabel "reading"
set ylabel "tlt [counts]"
plot "tilt.csv" using 0:"tlt_front_counts" with points pt 7 ps 0.3 title "tlt^f", \
     "" using 0:"tlt_rear_counts" with points pt 7 ps 0.3 title "tlt^r"
)gp";

Recording readings_recording(const TiltPlacements& placements) {
  Recording r;
  r.name = "tilt";
  r.title = "Procedure 3.4: tlt^f, tlt^r at the stops and level";
  r.columns = {"placement", "tlt_front_counts", "tlt_rear_counts"};
  for (std::size_t k = 0; k < placements.size(); ++k) {
    const TiltPlacement& p = placements[k];
    const std::size_t n = std::min(p.front_counts.size(), p.rear_counts.size());
    for (std::size_t i = 0; i < n; ++i) {
      r.rows.push_back({static_cast<double>(k + 1), p.front_counts[i], p.rear_counts[i]});
    }
  }
  r.gnuplot = kGnuplot;
  return r;
}

}  // namespace

TiltFit fit_tilt_channel(const std::array<double, 4>& m, double stop_rad) {
  TiltFit fit;
  const double upper_span = m[0] - m[3];  // from −b/2 to θs − b/2
  const double lower_span = m[1] - m[2];  // from −θs + b/2 to +b/2
  fit.gain_rad_per_count = 2.0 * stop_rad / (upper_span + lower_span);
  fit.offset_rad = -fit.gain_rad_per_count * (m[1] + m[3]) / 2.0;
  fit.play_rad = fit.gain_rad_per_count * (m[1] - m[3]);
  fit.span_mismatch_counts = upper_span - lower_span;
  return fit;
}

ProcedureResult fit_tilt(const TiltPlacements& placements, const SensorParams& configured,
                         const TiltLimits& limits) {
  ProcedureResult result;
  const ChannelMeans front = channel_means(placements, true, limits, result);
  const ChannelMeans rear = channel_means(placements, false, limits, result);
  if (!result.problems.empty()) return result;
  const TiltFit f = fit_tilt_channel(front.means);
  const TiltFit r = fit_tilt_channel(rear.means);
  judge(f, configured.tilt_front.gain, "θf", limits, result);
  judge(r, configured.tilt_rear.gain, "θr", limits, result);
  result.quality["max_rest_sd_counts"] = std::max(front.worst_sd, rear.worst_sd);
  result.quality["front_span_mismatch_counts"] = f.span_mismatch_counts;
  result.quality["rear_span_mismatch_counts"] = r.span_mismatch_counts;
  result.quality["front_play_rad"] = f.play_rad;
  result.quality["rear_play_rad"] = r.play_rad;
  result.notes.push_back("the potentiometers' play: θf " + fixed(f.play_rad * 180.0 / std::numbers::pi, 1) +
                         "°, θr " + fixed(r.play_rad * 180.0 / std::numbers::pi, 1) +
                         "° (the thesis: an error of about ±8°); taken out of the fit");

  toml::table sensors;
  sensors.insert_or_assign("tilt_front_rad_per_count", rounded(f.gain_rad_per_count, 1e8));
  sensors.insert_or_assign("tilt_front_offset_rad", rounded(f.offset_rad, 1e6));
  sensors.insert_or_assign("tilt_rear_rad_per_count", rounded(r.gain_rad_per_count, 1e8));
  sensors.insert_or_assign("tilt_rear_offset_rad", rounded(r.offset_rad, 1e6));
  result.values.insert_or_assign("sensors", std::move(sensors));
  result.recordings.push_back(readings_recording(placements));
  return result;
}

namespace {

// Procedure 3.4 on the stand: both exterior axles held by hand in the four placements in turn.
class TiltProcedure final : public Procedure {
 public:
  double default_duration_s() const override { return kDefaultRestS * 4.0; }

  void command(Bench& bench, const Run& run) override {
    const double rest_s = run.duration_s / 4.0;
    for (std::size_t k = 0; k < kPoses.size(); ++k) {
      BenchSetup setup;
      setup.placement = BenchSetup::Placement::kStand;
      setup.axle_tilt_rad = {kPoses[k].tilt_rad, kPoses[k].tilt_rad};
      setup.instruction = kPoses[k].instruction;
      bench.arrange(setup);
      for (const BenchSample& s : bench.hold(MotorVector{}, rest_s)) {
        if (!s.raw) continue;
        const bool front = s.raw->tilt_channel == protocol::TiltChannel::kFront;
        (front ? placements_[k].front_counts : placements_[k].rear_counts)
            .push_back(static_cast<double>(s.raw->tlt));
      }
    }
  }

  std::optional<BenchSetup> teardown(const Run&) const override {
    BenchSetup ground;
    ground.instruction = "Procedure 3.4 done: let go of the axles and set the rover on its wheels";
    return ground;
  }

  ProcedureResult fit(const Run& run) const override {
    return fit_tilt(placements_, run.params.sensors);
  }

 private:
  TiltPlacements placements_{};
};

}  // namespace

std::unique_ptr<Procedure> tilt_procedure() { return std::make_unique<TiltProcedure>(); }

}  // namespace marsokhod::calibration
