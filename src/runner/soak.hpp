// `marsokhod soak`: hours of seeded random operation with faults switched on and off at random,
// every invariant of soak_checker.hpp checked every cycle. RELIABILITY.md reports the results.
//
// The run is cut into segments of at most segment_s (10 min) simulated time, alternately on hard
// ground and on sand, the soil model (a short run has one of each), each a fresh Session — a
// rover with a fresh battery and a driver that starts up — with its own seeds derived from the
// soak's seed. The same seed gives the same run, bit for bit (simulated time only; the wall clock
// is only reported).
//
// The first violation is written as a replayable recording of the window_s (30 s) before it,
// up to and including the violating cycle: the segment is run again (deterministically) with a
// Recorder from the window's start, and soak.json says where in the soak the window lies. A
// driver in the middle of its life has state from before the window, so replaying the window
// needs that driver: soak_window_driver() runs the segment again to the window's start and hands
// its driver over to replay() — `marsokhod replay DIR` does this when DIR has a soak.json.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/params.hpp"
#include "driver/driver.hpp"
#include "runner/soak_checker.hpp"
#include "runner/soak_faults.hpp"
#include "runner/soak_script.hpp"

namespace marsokhod::runner {

struct SoakOptions {
  double hours = 1.0;        // simulated
  std::uint64_t seed = 1;
  std::filesystem::path out;  // the first violation's recording; empty: none is written
  std::filesystem::path config_file;       // copied into the recording
  std::filesystem::path calibration_file;  // the driver's, copied too when given
  const Params* rover_params = nullptr;    // the nominal configuration (default: the driver's)
  double window_s = 30.0;
  double segment_s = 600.0;
  CheckerLimits limits;
};

struct SoakViolation {
  Violation violation;
  std::size_t segment = 0;
  bool sand = false;
  double soak_time_s = 0.0;  // from the soak's start (the segment's start + its session time)
};

struct SoakResult {
  std::uint64_t seed = 0;
  double sim_hours = 0.0;
  double wall_time_s = 0.0;
  double real_time_factor = 0.0;
  std::size_t segments = 0;
  std::uint64_t cycles = 0;
  std::uint64_t evaluations = 0;  // invariants checked
  std::array<std::uint64_t, kFaultKindCount> faults_injected{};
  std::array<double, kFaultKindCount> fault_active_s{};
  OperatorStats operator_stats;
  std::uint64_t driver_restarts = 0;
  std::uint64_t spurious_silent_faults = 0;
  std::uint64_t missions_reached = 0;  // the operator's turn/move/goto missions, as they ended
  std::uint64_t missions_aborted = 0;
  double max_joint_excess_rad = 0.0;  // the farthest a joint went outside (5.3), as judged
  std::optional<SoakViolation> max_joint_excess_at;  // where (when above 0): its cycle and detail
  double max_unknown_joint_excess_rad = 0.0;  // the truth of joints the driver could not know
  double max_down_joint_excess_rad = 0.0;  // the joints outside (5.3) while the driver was down
  std::array<std::uint64_t, kInvariantCount> violations{};  // per invariant
  std::vector<SoakViolation> first_violations;               // the first of each, as found
  std::optional<std::filesystem::path> recording;            // of the very first
  std::string recording_note;  // why none was written, or a determinism problem
  std::uint64_t total_violations() const;
};

// Called as each invariant is first violated (the app prints it at once).
using ViolationReport = std::function<void(const SoakViolation&)>;

SoakResult run_soak(const Params& params, const SoakOptions& options,
                    const ViolationReport& report = {});

nlohmann::ordered_json to_json(const SoakResult& result);

// The driver at the start of a soak's recording (DIR/soak.json), as it was before the window's
// first cycle: nullptr when DIR is not a soak's recording or the window starts without a running
// driver (replay then starts one, as the soak did). Throws std::runtime_error for an unreadable
// soak.json. `driver_params` must outlive the driver.
std::unique_ptr<driver::Driver> soak_window_driver(const std::filesystem::path& folder,
                                                   const Params& driver_params,
                                                   const Params& rover_params);

}  // namespace marsokhod::runner
