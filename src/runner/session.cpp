#include "runner/session.hpp"

#include <cmath>

namespace marsokhod::runner {

Session::Session(const Params& params, const sim::SimOptions& options)
    : Session(params, params, options) {}

Session::Session(const Params& rover_params, const Params& driver_params,
                 const sim::SimOptions& options)
    : params_(&driver_params),
      rover_(rover_params, options),
      driver_(std::make_unique<driver::Driver>(driver_params)),
      runtime_(driver_->runtime()),
      cycle_us_(std::llround(driver_params.cycle.period_s * 1e6)) {}

void Session::set_runtime(const driver::RuntimeSettings& settings) {
  driver::validate(settings);
  runtime_ = settings;
  if (driver_) driver_->set_runtime(settings);
}

const CycleRecord& Session::step(const driver::OperatorInput* input) {
  record_ = CycleRecord{};
  record_.time_us = time_us_;
  const double t = static_cast<double>(time_us_) * 1e-6;
  record_.received = rover_.advance_to(t);
  if (halted_) {
    record_.driver_running = false;
    time_us_ += cycle_us_;
    ++cycles_;
    return record_;
  }
  if (!rover_.computer_on()) {
    driver_.reset();  // the onboard computer is down, and the driver with it
  } else if (!driver_) {
    // Rebooted: a fresh start-up, continuing from the kept joint state if it is recent.
    std::optional<driver::JointMemory> kept;
    if (kept_joints_ && t - kept_time_s_ <= params_->safety.joint_memory_max_age_s) {
      kept = kept_joints_;
      record_.kept_joints = kept_joints_;
    }
    driver_ = std::make_unique<driver::Driver>(*params_, kept);
    driver_->set_runtime(runtime_);
    ++restarts_;
  }
  record_.driver_running = driver_ != nullptr;
  record_.input = input;
  if (driver_) {
    std::vector<protocol::CanFrame> frames;
    frames.reserve(record_.received.size());
    for (const sim::TimedFrame& f : record_.received) frames.push_back(f.frame);
    record_.sent = driver_->step(t, frames, input);
    for (const protocol::CanFrame& f : record_.sent) rover_.send(f, t);
    last_status_ = driver_->status();
    kept_joints_ = driver_->joint_memory();
    kept_time_s_ = t;
  }
  time_us_ += cycle_us_;
  ++cycles_;
  return record_;
}

void follow_truth_odometry(const Session& session, const CycleRecord& cycle,
                           estimation::OdometryFrameTracker& tracker) {
  const sim::GroundTruth t = session.rover().truth();
  const driver::DriverStatus& s = session.status();
  tracker.observe(t.position_m[0], t.position_m[1], t.roll_pitch_yaw_rad[2],
                  cycle.driver_running &&
                      (s.cycle == 1 || s.startup_phase != driver::StartupPhase::kDone));
}

}  // namespace marsokhod::runner
