#include "calibration/joints.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "calibration/fit.hpp"
#include "calibration/procedures.hpp"
#include "core/adaptation/backlash.hpp"
#include "core/adaptation/motor_curve.hpp"
#include "core/adaptation/no_load_velocity.hpp"
#include "driver/startup.hpp"

namespace marsokhod::calibration {
namespace {

constexpr std::array<std::size_t, 2> kJoints{kFrontJoint, kRearJoint};
constexpr double kReversalDuty = 0.1;  // Procedure 4.1: d = ±0.1
constexpr double kHoldS = 2.5;         // the rear gap (≈ 0.25 rad) at ≈ 0.2 rad/s, then rest
constexpr double kRestWindowS = 0.25;  // the end of a hold that is averaged
constexpr std::size_t kDefaultReversals = 6;

JointHold hold_joints_end(const std::vector<BenchSample>& samples, std::size_t motor, double duty,
                          double window_s) {
  const double end_s = samples.back().time_s;
  std::vector<double> shaft, speed;
  for (const BenchSample& s : samples) {
    if (s.time_s < end_s - window_s) continue;
    shaft.push_back(s.position_rad[motor]);
    speed.push_back(std::abs(s.velocity_radps[motor]));
  }
  return {duty, mean(shaft), mean(speed)};
}

constexpr const char* kGnuplot = R"gp(set xlabel "t [s]"
set ylabel "shaft position p-bar [rad]"
set y2label "duty"
set y2tics
plot "joints.csv" using "t_s":"front_shaft_rad" with lines title "p-bar 6 (front)", \
     "" using "t_s":"rear_shaft_rad" with lines title "p-bar 7 (rear)", \
     "" using "t_s":"front_duty" axes x1y2 with lines dt 2 title "d6", \
     "" using "t_s":"rear_duty" axes x1y2 with lines dt 2 title "d7"
)gp";

}  // namespace

ProcedureResult fit_joints(const std::array<std::vector<JointHold>, 2>& holds,
                           const JointInitialisation& initialisation,
                           const MotorParams& configured, const JointLimits& limits) {
  ProcedureResult result;
  result.quality["initialisation_s"] = initialisation.duration_s;
  result.quality["initialisation_front_travel_rad"] = initialisation.travel_rad[0];
  result.quality["initialisation_rear_travel_rad"] = initialisation.travel_rad[1];
  MotorVector backlash = configured.backlash_rad;
  for (std::size_t j = 0; j < 2; ++j) {
    const std::size_t motor = kJoints[j];
    const std::string name = j == 0 ? "front" : "rear";
    std::vector<double> travels;
    for (std::size_t k = 0; k < holds[j].size(); ++k) {
      const JointHold& h = holds[j][k];
      if (h.rest_speed_radps > limits.max_rest_speed_radps) {
        result.problems.push_back(
            name + " joint: the shaft still turned at " + fixed(h.rest_speed_radps, 3) +
            " rad/s at the end of hold " + std::to_string(k + 1) + " (at most " +
            fixed(limits.max_rest_speed_radps, 3) +
            "): the joint moved; strap the rover down so that the joints cannot incline");
        continue;
      }
      if (k == 0) continue;
      const JointHold& before = holds[j][k - 1];
      if ((h.duty > 0.0) == (before.duty > 0.0)) continue;  // not a reversal
      if (before.rest_speed_radps > limits.max_rest_speed_radps) continue;
      travels.push_back(std::abs(h.rest_shaft_rad - before.rest_shaft_rad));
    }
    result.quality[name + "_reversals"] = static_cast<double>(travels.size());
    if (travels.size() < limits.min_travels) {
      result.problems.push_back(name + " joint: " + std::to_string(travels.size()) +
                                " reversals measured, at least " +
                                std::to_string(limits.min_travels) + " needed");
      continue;
    }
    const double b = mean(travels);
    const double spread = standard_deviation(travels);
    result.quality[name + "_backlash_rad"] = b;
    result.quality[name + "_backlash_sd_rad"] = spread;
    const double allowed = limits.max_spread_fraction * b + limits.max_spread_floor_rad;
    if (spread > allowed) {
      result.problems.push_back(name + " joint: the reversals disagree (σ " + fixed(spread, 4) +
                                " rad of " + fixed(b, 4) + " rad; at most " + fixed(allowed, 4) +
                                "): the joint is not held firmly or the shaft slips");
    }
    if (b < limits.min_backlash_rad || b > limits.max_backlash_rad) {
      result.problems.push_back(name + " joint: a backlash of " + fixed(b, 4) +
                                " rad is not plausible (" + fixed(limits.min_backlash_rad, 3) +
                                "–" + fixed(limits.max_backlash_rad, 3) +
                                " rad): the joint moved with the shaft or is disconnected");
    }
    backlash[motor] = b;
  }
  if (!result.problems.empty()) return result;
  toml::array vector;
  for (double b : backlash) vector.push_back(b);
  toml::table motors;
  motors.insert_or_assign("backlash_rad", std::move(vector));
  result.values.insert_or_assign("motors", std::move(motors));
  result.notes.push_back("the joints are initialised (Procedure 4.3): both shafts rest at the "
                         "negative end of their gaps, where the driver's start-up sets "
                         "p⁰ := p̄⁰ = ∓1.2121 rad");
  return result;
}

JointInitialisation initialise_joints(Bench& bench) {
  const Params& params = bench.params();
  driver::Startup startup(params);
  for (std::size_t i = 0; i < kMotorCount; ++i) startup.on_configured(i);  // bench.start() did
  startup.on_dead_man_acknowledged();
  JointInitialisation init;
  const BenchSample first = bench.last();
  const double start_s = first.time_s;
  MotorVector duty{};
  const adaptation::MotorCurve curve(
      adaptation::select_motor_curve(params.motor_curves, params.cycle.icr));
  // ν of the joint motors at the duty sent (4.3), for the start-up's meeting of shaft and joint.
  const auto no_load = [&](const BenchSample& s, std::size_t motor) {
    const double supply_v =
        s.sensors.supply_v > 1.0 ? s.sensors.supply_v : params.motors.nominal_supply_v;
    return adaptation::no_load_velocity(curve, s.duty[motor], params.motors.scale[motor], supply_v,
                                        params.motors.nominal_supply_v);
  };
  // Startup times out after 3 s; the margin lets the duty rules bring the motors to rest.
  const auto max_cycles = static_cast<long>(std::ceil(2.0 * driver::kCalibrationTimeout_s /
                                                      bench.period_s()));
  for (long k = 0; k < max_cycles && startup.phase() != driver::StartupPhase::kDone; ++k) {
    const BenchSample& s = bench.cycle(duty);
    const auto d = startup.calibrate(
        s.time_s, {s.position_rad[kFrontJoint], s.position_rad[kRearJoint]},
        {s.velocity_radps[kFrontJoint], s.velocity_radps[kRearJoint]},
        {no_load(s, kFrontJoint), no_load(s, kRearJoint)});
    duty[kFrontJoint] = d[0];
    duty[kRearJoint] = d[1];
  }
  init.duration_s = bench.last().time_s - start_s;
  init.timed_out = init.duration_s >= driver::kCalibrationTimeout_s;
  init.dragged_rad = startup.over_travel_rad();
  bench.stop();
  for (std::size_t j = 0; j < 2; ++j) {
    init.travel_rad[j] = first.position_rad[kJoints[j]] - bench.last().position_rad[kJoints[j]];
  }
  return init;
}

JointMover::JointMover(const Bench& bench, std::array<double, 2> dragged_rad) {
  for (std::size_t j = 0; j < 2; ++j) {
    const std::size_t motor = kJoints[j];
    backlash_rad_[j] = bench.params().motors.backlash_rad[motor];
    // Procedure 4.3: p⁰ := p̄⁰ = ∓1.2121 with the shaft at the negative end of its gap, less the
    // drag after the shaft met its joint.
    joint_rad_[j] = bench.params().motors.initial_position_rad[motor] - dragged_rad[j];
    shaft_offset_rad_[j] = joint_rad_[j] - bench.last().position_rad[motor];
  }
}

void JointMover::track(const BenchSample& sample) {
  for (std::size_t j = 0; j < 2; ++j) {
    joint_rad_[j] = adaptation::backlash_position(
        sample.position_rad[kJoints[j]] + shaft_offset_rad_[j], joint_rad_[j], backlash_rad_[j]);
  }
}

bool JointMover::move_to(Bench& bench, double front_rad, double rear_rad, double tolerance_rad,
                         double timeout_s) {
  // Small duty cycles near the target, so that the slew-limited stop overshoots little.
  constexpr double kMinDuty = 0.18, kMaxDuty = 0.4, kDutyPerRad = 2.0;
  const std::array<double, 2> target{front_rad, rear_rad};
  const auto cycles = static_cast<long>(std::ceil(timeout_s / bench.period_s()));
  MotorVector duty{};
  for (long k = 0; k < cycles; ++k) {
    track(bench.cycle(duty));
    bool arrived = true;
    for (std::size_t j = 0; j < 2; ++j) {
      const double error = target[j] - joint_rad_[j];
      const bool here = std::abs(error) <= tolerance_rad;
      arrived = arrived && here;
      duty[kJoints[j]] =
          here ? 0.0 : std::copysign(std::min(kMaxDuty, kMinDuty + kDutyPerRad * std::abs(error)),
                                     error);
    }
    if (arrived) {
      bench.stop();
      track(bench.last());
      return true;
    }
  }
  bench.stop();
  track(bench.last());
  return false;
}

namespace {

// Procedures 4.1/4.3 strapped to the ground: the joints initialised, then their shafts reversed
// at d = ±0.1 across the backlash, hold after hold.
class JointsProcedure final : public Procedure {
 public:
  double default_duration_s() const override {
    return kHoldS * static_cast<double>(kDefaultReversals);
  }

  void command(Bench& bench, const Run& run) override {
    BenchSetup setup;
    setup.placement = BenchSetup::Placement::kGround;
    setup.strapped_down = true;
    setup.instruction =
        "Procedures 4.1/4.3: joints in vertical configuration (as after start-up); strap the "
        "rover to the ground so that neither the wheels rotate nor the joints incline";
    bench.arrange(setup);
    init_ = initialise_joints(bench);
    const std::size_t reversals =
        std::max<std::size_t>(2, static_cast<std::size_t>(run.duration_s / kHoldS));
    // Alternating +, −, …, ending with − so that the shafts rest at the negative end of the gap,
    // the state Procedure 4.3 leaves.
    for (std::size_t k = 0; k < reversals + 1; ++k) {
      const double d = (reversals - k) % 2 == 0 ? -kReversalDuty : kReversalDuty;
      MotorVector duty{};
      duty[kFrontJoint] = d;
      duty[kRearJoint] = d;
      const std::vector<BenchSample> samples = bench.hold(duty, kHoldS);
      for (const BenchSample& s : samples) {
        rows_.push_back({s.time_s, s.duty[kFrontJoint], s.position_rad[kFrontJoint],
                         s.velocity_radps[kFrontJoint], s.duty[kRearJoint],
                         s.position_rad[kRearJoint], s.velocity_radps[kRearJoint]});
      }
      for (std::size_t j = 0; j < 2; ++j) {
        holds_[j].push_back(hold_joints_end(samples, kJoints[j], d, kRestWindowS));
      }
    }
  }

  std::optional<BenchSetup> teardown(const Run&) const override {
    BenchSetup free;
    free.instruction = "Procedure 4.1 done: unstrap the rover (the joints stay as they are)";
    return free;
  }

  ProcedureResult fit(const Run& run) const override {
    ProcedureResult result = fit_joints(holds_, init_, run.params.motors);
    Recording r;
    r.name = "joints";
    r.title = "Procedure 4.1: joint shafts reversed at d = ±0.1 across the backlash";
    r.columns = {"t_s", "front_duty", "front_shaft_rad", "front_speed_radps",
                 "rear_duty", "rear_shaft_rad", "rear_speed_radps"};
    r.rows = rows_;
    r.gnuplot = kGnuplot;
    result.recordings.push_back(std::move(r));
    return result;
  }

 private:
  JointInitialisation init_;
  std::array<std::vector<JointHold>, 2> holds_;
  std::vector<std::vector<double>> rows_;
};

}  // namespace

std::unique_ptr<Procedure> joints_procedure() { return std::make_unique<JointsProcedure>(); }

}  // namespace marsokhod::calibration
