#include "core/behaviour/switches.hpp"

namespace marsokhod::behaviour {

BehaviourSwitches switches_from_params(const BehaviourParams& behaviours,
                                       const LoadDistributionParams& load_distribution) {
  return BehaviourSwitches{behaviours.power_management, behaviours.slant_response,
                           behaviours.contract_on_turn, behaviours.axle_placement,
                           load_distribution.mode};
}

BehaviourSwitches all_switched_off() {
  return BehaviourSwitches{false, false, false, false, LoadDistributionMode::kOff};
}

}  // namespace marsokhod::behaviour
