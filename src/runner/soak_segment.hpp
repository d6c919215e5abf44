// One segment of a soak (soak.hpp): a Session on hard ground or sand driven by the random
// operator, with the fault schedule and the invariant checker, one cycle at a time. The soak,
// the re-run that records a violation's window and the re-run that hands replay its driver all
// step the same SegmentRunner, so they see the same cycles, bit for bit.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <memory>
#include <optional>
#include <vector>

#include "runner/recorder.hpp"
#include "runner/session.hpp"
#include "runner/soak_checker.hpp"
#include "runner/soak_faults.hpp"
#include "runner/soak_script.hpp"

namespace marsokhod::runner {

struct SegmentPlan {
  std::size_t index = 0;
  std::uint64_t seed = 0;  // the simulated unit's; the operator's and the faults' derive from it
  bool sand = false;
  std::int64_t start_us = 0;     // in the soak
  std::int64_t duration_us = 0;
};

// The segments of a soak of `hours` with the given seed and segment length: at most
// segment_s each, alternately hard ground and sand, two halves for a run under 2·segment_s.
std::vector<SegmentPlan> plan_segments(double hours, std::uint64_t seed, double segment_s,
                                       double period_s);

class SegmentRunner {
 public:
  SegmentRunner(const SegmentPlan& plan, const Params& driver_params, const Params& rover_params,
                const CheckerLimits& limits);

  bool done() const { return time_us() >= plan_.duration_us; }
  std::int64_t time_us() const {
    return static_cast<std::int64_t>(session_.cycles()) * session_.cycle_us();
  }
  // One cycle: faults due, the operator's input, the session's step, the invariants. With a
  // recorder the cycle is recorded (`first` writes the run-time settings, as replay needs).
  std::vector<Violation> step(Recorder* recorder = nullptr, bool first = false);

  Session& session() { return session_; }
  const OperatorScript& script() const { return script_; }
  const FaultSchedule& faults() const { return faults_; }
  const InvariantChecker& checker() const { return checker_; }
  // "µN silent" faults latched while µN was answering in the simulator (lost frames alone).
  std::uint64_t spurious_silent_faults() const { return spurious_silent_; }
  // The operator's turn, move and goto missions as the driver ended them (status.mission).
  std::uint64_t missions_reached() const { return missions_reached_; }
  std::uint64_t missions_aborted() const { return missions_aborted_; }

 private:
  void count_spurious_faults(std::int64_t time_us, const driver::DriverStatus& status,
                             const sim::SimFaults& faults);
  void count_mission_end(const driver::DriverStatus& status);

  SegmentPlan plan_;
  Session session_;
  OperatorScript script_;
  FaultSchedule faults_;
  InvariantChecker checker_;
  int missed_limit_;
  std::vector<protocol::CanFrame> received_;
  std::vector<std::string> faults_before_;
  std::array<std::optional<std::int64_t>, kMotorCount + 1> silenced_us_{};  // last made silent
  std::uint64_t spurious_silent_ = 0;
  std::uint64_t ended_mission_id_ = 0;  // the driver's id of the last mission counted (per driver)
  std::uint64_t missions_reached_ = 0;
  std::uint64_t missions_aborted_ = 0;
};

}  // namespace marsokhod::runner
