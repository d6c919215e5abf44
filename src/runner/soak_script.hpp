// The soak's random operator (`marsokhod soak`): a seeded script of what an operator does for
// hours — drive, spin, trench, move the joints (by speed and to positions), run every gait
// forward and back, drive by cmd_vel (velocity), send missions (turn, move, goto, some with
// their own standing) and keep them alive with heartbeats, stop, hand control over to another
// console, fall silent — from a console that sends targets or from a gamepad, at 64 Hz with
// dropped messages. Deterministic: the same seed and the same driver statuses give the same
// inputs (no wall clock, and a portable mapping of std::mt19937_64's bits to numbers, not the
// library's distributions).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <random>

#include "core/params.hpp"
#include "driver/operator_commands.hpp"
#include "driver/status.hpp"

namespace marsokhod::runner {

// std::mt19937_64 with the same numbers on every standard library.
class SoakRandom {
 public:
  explicit SoakRandom(std::uint64_t seed) : engine_(seed) {}
  double uniform(double lo, double hi);      // [lo, hi)
  std::size_t below(std::size_t n);          // 0 … n − 1
  bool chance(double probability) { return uniform(0.0, 1.0) < probability; }

 private:
  std::mt19937_64 engine_;
};

// A well-mixed seed for stream `stream` of `seed` (SplitMix64).
std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t stream);

enum class Activity : std::uint8_t {
  kDrive, kSpin, kTrench, kDriveAndSpin, kJoints, kJointTargets, kGait, kStop, kHandOver,
  kSilence, kVelocity, kMission,
};
inline constexpr std::size_t kActivityCount = 12;
const char* activity_name(Activity activity);

struct OperatorStats {
  std::array<std::uint64_t, kActivityCount> activities{};
  std::uint64_t commands = 0;        // inputs sent
  std::uint64_t short_silences = 0;  // shorter than the operator timeout
  std::uint64_t long_silences = 0;   // longer: the driver must stop the rover
  std::uint64_t hand_overs = 0;
  std::uint64_t fault_clears = 0;    // inputs that asked to clear latched faults
  std::uint64_t heartbeats = 0;      // sent while a mission of the script's ran
};

class OperatorScript {
 public:
  OperatorScript(std::uint64_t seed, const Params& params);

  // The operator's input for the cycle at time_us, or nullptr when nothing arrives this cycle.
  // `status` is the driver's latest (an operator clears latched faults a while after seeing them).
  const driver::OperatorInput* next(std::int64_t time_us, const driver::DriverStatus& status);
  const OperatorStats& stats() const { return stats_; }

 private:
  void start_activity(std::int64_t time_us, const driver::DriverStatus& status);
  navigation::MissionRequest random_mission(const driver::DriverStatus& status);
  driver::OperatorInput command(bool first_cycle);
  driver::OperatorInput gamepad_command(bool first_cycle) const;

  const Params* params_;
  SoakRandom random_;
  OperatorStats stats_;
  Activity activity_ = Activity::kSilence;
  std::int64_t activity_end_us_ = 0;
  std::int64_t activity_start_us_ = 0;
  bool use_gamepad_ = false;  // the console in control sends gamepad readings, else targets
  mobility::OperatorTargets targets_;  // this activity's, in targets form
  navigation::VelocityCommand velocity_;   // kVelocity's
  navigation::MissionRequest mission_;     // kMission's, sent on its first cycle
  std::optional<std::int64_t> clear_at_us_;
  driver::OperatorInput input_;
};

}  // namespace marsokhod::runner
