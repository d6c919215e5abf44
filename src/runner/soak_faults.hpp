// The soak's faults (`marsokhod soak`): every 10–50 s of simulated time one of the fault
// kinds is switched on for 5–45 s (a brown-out is a single event: the onboard computer reboots
// for 30 s) — 1 % frame loss, lost encoder pulses, a silent controller, battery sag, a blocked
// wheel, a wheel in the air, a brown-out — so that several may overlap. Seeded, deterministic.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "runner/soak_script.hpp"
#include "sim/rover/simulated_rover.hpp"

namespace marsokhod::runner {

enum class FaultKind : std::uint8_t {
  kFrameLoss, kLostPulses, kSilentController, kBatterySag, kBlockedWheel, kWheelInAir, kBrownout,
};
inline constexpr std::size_t kFaultKindCount = 7;
const char* fault_kind_name(FaultKind kind);  // "frame-loss", …

struct FaultChange {
  FaultKind kind = FaultKind::kFrameLoss;
  bool on = true;
  std::string what;  // "µ3 silent", "wheel 2 blocked", "battery sag 0.52 Ω"
};

class FaultSchedule {
 public:
  explicit FaultSchedule(std::uint64_t seed);

  // Switches the faults due at time_us on the rover; returns what changed.
  std::vector<FaultChange> update(std::int64_t time_us, sim::SimulatedRover& rover);

  const std::array<std::uint64_t, kFaultKindCount>& injected() const { return injected_; }
  // Simulated time each kind was on (a brown-out: the reboot time it caused).
  std::array<double, kFaultKindCount> active_s() const;

 private:
  struct Active {
    FaultKind kind;
    std::int64_t until_us;
    std::size_t target;  // the controller, motor or wheel
    std::string what;
  };
  FaultChange switch_on(FaultKind kind, std::int64_t time_us, sim::SimFaults& faults);
  static void switch_off(const Active& active, sim::SimFaults& faults);

  SoakRandom random_;
  std::int64_t next_us_;
  std::int64_t last_us_ = 0;
  std::vector<Active> active_;
  std::array<std::uint64_t, kFaultKindCount> injected_{};
  std::array<std::int64_t, kFaultKindCount> active_us_{};
  bool computer_was_on_ = true;
};

}  // namespace marsokhod::runner
