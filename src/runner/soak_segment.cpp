#include "runner/soak_segment.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace marsokhod::runner {
namespace {

// Streams of derive_seed() per segment seed.
constexpr std::uint64_t kOperatorStream = 1;
constexpr std::uint64_t kFaultStream = 2;

sim::SimOptions sim_options(const SegmentPlan& plan) {
  sim::SimOptions options;
  options.seed = plan.seed;
  options.terrain.kind = sim::TerrainKind::kFlat;
  options.terrain.ground = plan.sand ? sim::sand() : sim::hard_ground();
  options.supply = sim::SupplyKind::kBattery;
  return options;
}

}  // namespace

std::vector<SegmentPlan> plan_segments(double hours, std::uint64_t seed, double segment_s,
                                       double period_s) {
  const auto cycle_us = std::llround(period_s * 1e6);
  const auto whole_cycles = [cycle_us](double s) {
    return std::max<std::int64_t>(1, std::llround(s * 1e6 / static_cast<double>(cycle_us))) *
           cycle_us;
  };
  const double total_s = hours * 3600.0;
  std::vector<std::int64_t> durations;
  if (total_s <= 2.0 * segment_s) {
    durations = {whole_cycles(total_s / 2.0), whole_cycles(total_s / 2.0)};
  } else {
    double left_s = total_s;
    while (left_s > 1e-9) {
      durations.push_back(whole_cycles(std::min(segment_s, left_s)));
      left_s -= std::min(segment_s, left_s);
    }
  }
  std::vector<SegmentPlan> plans;
  std::int64_t start_us = 0;
  for (std::size_t i = 0; i < durations.size(); ++i) {
    plans.push_back({i, derive_seed(seed, i), i % 2 == 1, start_us, durations[i]});
    start_us += durations[i];
  }
  return plans;
}

SegmentRunner::SegmentRunner(const SegmentPlan& plan, const Params& driver_params,
                             const Params& rover_params, const CheckerLimits& limits)
    : plan_(plan),
      session_(rover_params, driver_params, sim_options(plan)),
      script_(derive_seed(plan.seed, kOperatorStream), driver_params),
      faults_(derive_seed(plan.seed, kFaultStream)),
      checker_(driver_params, limits),
      missed_limit_(driver_params.safety.missed_responses_limit) {}

std::vector<Violation> SegmentRunner::step(Recorder* recorder, bool first) {
  sim::SimulatedRover& rover = session_.rover();
  const std::int64_t now_us = time_us();
  faults_.update(now_us, rover);
  const driver::OperatorInput* input = script_.next(now_us, session_.status());
  const CycleRecord& cycle = session_.step(input);
  if (recorder != nullptr) {
    recorder->record(cycle, first ? std::optional(session_.runtime()) : std::nullopt,
                     session_.status(), rover);
  }
  received_.clear();
  for (const sim::TimedFrame& f : cycle.received) received_.push_back(f.frame);
  CycleView view;
  view.time_us = cycle.time_us;
  view.driver_running = cycle.driver_running;
  view.status = cycle.driver_running ? &session_.status() : nullptr;
  view.received = received_;
  view.sent = cycle.sent;
  view.operator_command = cycle.driver_running && input != nullptr &&
                          (input->gamepad || input->targets || input->velocity ||
                           input->mission || input->heartbeat || input->stop);
  const sim::GroundTruth truth = rover.truth();
  view.joint_angle_rad = {truth.joint_angle_rad[kFrontJoint], truth.joint_angle_rad[kRearJoint]};
  view.motor_duty = rover.firmware().duty();
  view.stop_frames_lost = rover.firmware().stop_frames_lost();
  view.supply_v = rover.electrics().supply_v;
  const sim::SimFaults& f = rover.faults();
  view.joint_encoder_fault = {f.lost_pulse_fraction[kFrontJoint] > 0.0,
                              f.lost_pulse_fraction[kRearJoint] > 0.0};
  if (cycle.driver_running) {
    count_spurious_faults(cycle.time_us, session_.status(), f);
    count_mission_end(session_.status());
  } else {
    ended_mission_id_ = 0;  // a restarted driver counts its missions from 1 again
  }
  return checker_.check(view);
}

void SegmentRunner::count_mission_end(const driver::DriverStatus& status) {
  const navigation::MissionStatus& m = status.mission;
  if (m.id <= ended_mission_id_ || m.kind == navigation::MissionKind::kVelocity) return;
  if (m.state == navigation::MissionState::kReached) {
    ++missions_reached_;
  } else if (m.state == navigation::MissionState::kAborted) {
    ++missions_aborted_;
  } else {
    return;
  }
  ended_mission_id_ = m.id;
}

void SegmentRunner::count_spurious_faults(std::int64_t time_us,
                                          const driver::DriverStatus& status,
                                          const sim::SimFaults& faults) {
  // A controller silenced within the last limit + 1 cycles explains its fault.
  const std::int64_t recent_us =
      session_.cycle_us() * (1 + missed_limit_);
  for (std::size_t i = 0; i <= kMotorCount; ++i) {
    if (faults.silent[i]) silenced_us_[i] = time_us;
  }
  for (const std::string& fault : status.faults) {
    if (std::find(faults_before_.begin(), faults_before_.end(), fault) != faults_before_.end()) {
      continue;
    }
    for (std::size_t i = 0; i <= kMotorCount; ++i) {
      const bool explained = silenced_us_[i] && time_us - *silenced_us_[i] <= recent_us;
      if (fault == "µ" + std::to_string(i) + " silent" && !explained) ++spurious_silent_;
    }
  }
  faults_before_ = status.faults;
}

}  // namespace marsokhod::runner
