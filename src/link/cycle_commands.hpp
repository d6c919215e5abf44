// The console's commands of one control cycle (LinkServer::take_inbound), merged into what the
// driver takes at that cycle: the newest operator input — but a stop wins its cycle, no later
// input of the same cycle replaces it, and a mission is not replaced by a heartbeat — with the stop's reason (shown until the operator
// re-arms), and the run-time settings after every configure of the cycle, in order.
#pragma once

#include <optional>
#include <vector>

#include "driver/operator_commands.hpp"
#include "link/control_arbiter.hpp"

namespace marsokhod::link {

struct CycleCommands {
  std::optional<driver::OperatorInput> input;       // none: nothing for the driver arrived
  std::optional<driver::RuntimeSettings> settings;  // set when a configure arrived
};

// `current`: the settings in force, which the configures change.
CycleCommands merge_cycle_commands(const std::vector<InboundCommand>& commands,
                                   const driver::RuntimeSettings& current);

}  // namespace marsokhod::link
