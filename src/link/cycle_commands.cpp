#include "link/cycle_commands.hpp"

namespace marsokhod::link {

CycleCommands merge_cycle_commands(const std::vector<InboundCommand>& commands,
                                   const driver::RuntimeSettings& current) {
  CycleCommands merged;
  for (const InboundCommand& command : commands) {
    if (const auto* configure = std::get_if<ConfigureMessage>(&command.message)) {
      merged.settings = configure->change.applied_to(merged.settings.value_or(current));
      continue;
    }
    auto next = operator_input(command.message);
    if (!next) continue;
    if (next->stop) next->stop_reason = command.reason;  // shown until the operator re-arms
    if (merged.input && merged.input->stop && !next->stop) continue;  // a stop holds its cycle
    // A mission holds its cycle against a heartbeat (which adds nothing to it); any other
    // later input replaces it as it would a cycle later.
    if (merged.input && merged.input->mission && next->heartbeat) continue;
    merged.input = next;
  }
  return merged;
}

}  // namespace marsokhod::link
