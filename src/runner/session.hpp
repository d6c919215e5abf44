// The embedded rover: the simulated rover and the driver in lockstep on an in-process bus, the
// way `marsokhod run` and `marsokhod scenario` use them. Time is a value: cycle k runs at
// t_k = k·h (whole microseconds, so that a recording's timestamps give back the same numbers in
// replay). Each cycle:
//   1. the rover runs to t_k and hands over the frames its controllers delivered (with the bus
//      model's timing: the responses to the requests of cycle k−1);
//   2. the driver steps with them and the operator's input of this cycle;
//   3. its requests go onto the bus at t_k.
// While the simulated onboard computer is browned out the driver is down (it runs on that
// computer); when it comes back a fresh driver starts up, as after a reboot, with the joint state
// the last one kept (driver/joint_memory.hpp) if it is at most safety.joint_memory_max_age_s old
// — the simulated onboard computer's stand-in for the file `drive --joint-memory` writes.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "core/estimation/odometry_frame.hpp"
#include "core/params.hpp"
#include "driver/driver.hpp"
#include "sim/rover/simulated_rover.hpp"

namespace marsokhod::runner {

// What a recorder sees of one cycle.
struct CycleRecord {
  std::int64_t time_us = 0;                       // t_k
  std::vector<sim::TimedFrame> received;          // delivered to the driver before this step
  std::vector<protocol::CanFrame> sent;           // the driver's requests at t_k
  const driver::OperatorInput* input = nullptr;   // the operator's input of this cycle, if any
  bool driver_running = true;
  // A driver started this cycle after a restart, with this kept joint state (none: none).
  std::optional<driver::JointMemory> kept_joints;
};

class Session {
 public:
  Session(const Params& params, const sim::SimOptions& options);
  // The driver with its own (calibrated) Params, the simulated rover built from the nominal
  // configuration: the simulator's unit must not follow the driver's calibration.
  Session(const Params& rover_params, const Params& driver_params,
          const sim::SimOptions& options);

  // One cycle with the operator's input (nullptr: none arrived this cycle).
  const CycleRecord& step(const driver::OperatorInput* input = nullptr);

  std::int64_t cycle_us() const { return cycle_us_; }
  double time_s() const { return static_cast<double>(time_us_) * 1e-6; }
  std::uint64_t cycles() const { return cycles_; }
  sim::SimulatedRover& rover() { return rover_; }
  const sim::SimulatedRover& rover() const { return rover_; }
  bool driver_running() const { return driver_ != nullptr; }
  // The driver's status (the last one before a brown-out while it is down).
  const driver::DriverStatus& status() const { return last_status_; }
  driver::Driver* driver() { return driver_.get(); }
  // Hands the driver over as it stands (a replay continues from it, soak.hpp); the session is
  // not stepped any more afterwards. nullptr while the driver is down.
  std::unique_ptr<driver::Driver> take_driver() { return std::move(driver_); }
  // Run-time settings for the driver now and after any restart; throws std::invalid_argument.
  void set_runtime(const driver::RuntimeSettings& settings);
  const driver::RuntimeSettings& runtime() const { return runtime_; }
  // The driver stops stepping for good (a crash of the driver process): nothing is sent any more
  // and µ8's dead man's switch must stop the motors.
  void halt_driver() { halted_ = true; }
  bool driver_halted() const { return halted_; }
  std::uint64_t driver_restarts() const { return restarts_; }
  // The joint state kept for a restart, and the time it was kept [s].
  const std::optional<driver::JointMemory>& kept_joints() const { return kept_joints_; }

 private:
  const Params* params_;
  sim::SimulatedRover rover_;
  std::unique_ptr<driver::Driver> driver_;
  driver::RuntimeSettings runtime_;
  driver::DriverStatus last_status_;
  std::int64_t cycle_us_;
  std::int64_t time_us_ = 0;
  std::uint64_t cycles_ = 0;
  std::uint64_t restarts_ = 0;
  bool halted_ = false;
  CycleRecord record_;
  std::optional<driver::JointMemory> kept_joints_;
  double kept_time_s_ = 0.0;
};

// The simulator's true pose followed into the odometry frame of the session's driver, the frame
// its dead-reckoned status.pose is in: a (re)started driver's frame starts where its start-up ends
// (driver.cpp, update_pose: the pose stays zero until then), so the frame starts again at every
// cycle of a start-up (origin: the true middle of the centre axle and the true yaw then). After
// every step; while the driver is down the truth goes on in the last frame.
void follow_truth_odometry(const Session& session, const CycleRecord& cycle,
                           estimation::OdometryFrameTracker& tracker);

}  // namespace marsokhod::runner
