// Chapter 6: every behaviour can be switched on and off at run time. BehaviourSwitches is the
// driver's run-time copy of the configured switches (BehaviourParams' booleans and
// LoadDistributionParams::mode); each behaviour takes it and, when switched off, returns its
// neutral value: D = 1, the bounds (5.3), the joint targets unchanged, ρ as requested, h = 0.
#pragma once

#include "core/params.hpp"

namespace marsokhod::behaviour {

struct BehaviourSwitches {
  bool power_management = true;  // (6.3)
  bool slant_response = true;    // 6.2.1, (6.4)
  bool contract_on_turn = true;  // 6.2.2
  bool axle_placement = true;    // 6.2.3
  // off, h^v (6.5) or h^s (6.6)
  LoadDistributionMode load_distribution = LoadDistributionMode::kOff;
  bool operator==(const BehaviourSwitches&) const = default;
};

// The switches as configured, the driver's starting point.
BehaviourSwitches switches_from_params(const BehaviourParams& behaviours,
                                       const LoadDistributionParams& load_distribution);

// Every behaviour off: the control of chapters 4 and 5 alone.
BehaviourSwitches all_switched_off();

}  // namespace marsokhod::behaviour
