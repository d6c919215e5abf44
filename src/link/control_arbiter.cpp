#include "link/control_arbiter.hpp"

namespace marsokhod::link {
namespace {

std::string client_name(ClientId id) { return "client " + std::to_string(id); }

// The stop that goes with a control change, queued after the change itself.
void add_stop(ArbiterOutcome& outcome, ClientId by, const std::string& reason) {
  outcome.inbound.push_back({by, StopMessage{}, reason});
  outcome.stopped = StopNotice{by, reason};
}

}  // namespace

ArbiterOutcome ControlArbiter::on_message(ClientId client, const OperatorMessage& message) {
  ArbiterOutcome outcome;
  if (std::holds_alternative<PingMessage>(message)) {
    outcome.pong = true;
  } else if (std::holds_alternative<TakeControlMessage>(message)) {
    outcome = take_control(client);
  } else if (std::holds_alternative<ReleaseControlMessage>(message)) {
    outcome = release_control(client);
  } else if (std::holds_alternative<StopMessage>(message)) {
    outcome = stop(client);
  } else if (controller_ == client) {
    outcome.inbound.push_back({client, message, ""});
  } else {
    outcome.error = MessageError{"type", kReadOnlyMessage};
  }
  return outcome;
}

ArbiterOutcome ControlArbiter::take_control(ClientId client) {
  ArbiterOutcome outcome;
  const std::optional<ClientId> previous = controller_;
  controller_ = client;
  if (previous == client) {
    // Already in control: repeat the state (the console may have missed it) but change nothing.
    outcome.change = ControlChange{client, previous, client_name(client) + " holds control"};
    outcome.change_to_sender_only = true;
    return outcome;
  }
  const std::string reason =
      previous ? client_name(client) + " took control from " + client_name(*previous)
               : client_name(client) + " took control";
  outcome.inbound.push_back({client, TakeControlMessage{}, ""});
  add_stop(outcome, client, reason);
  outcome.change = ControlChange{client, previous, reason};
  return outcome;
}

ArbiterOutcome ControlArbiter::release_control(ClientId client) {
  ArbiterOutcome outcome;
  if (controller_ != client) {
    outcome.error = MessageError{"type", kReadOnlyMessage};
    return outcome;
  }
  controller_.reset();
  const std::string reason = client_name(client) + " released control";
  outcome.inbound.push_back({client, ReleaseControlMessage{}, ""});
  add_stop(outcome, client, reason);
  outcome.change = ControlChange{std::nullopt, client, reason};
  return outcome;
}

ArbiterOutcome ControlArbiter::stop(ClientId client) {
  ArbiterOutcome outcome;
  std::string reason = client_name(client) + " pressed STOP";
  if (controller_ && *controller_ != client) {
    // Whoever pressed STOP saw something the holder did not: the holder must take control again
    // (and re-arm) to drive on.
    const ClientId holder = *controller_;
    controller_.reset();
    reason += "; " + client_name(holder) + " lost control";
    outcome.change = ControlChange{std::nullopt, holder, reason};
  }
  add_stop(outcome, client, reason);
  return outcome;
}

ArbiterOutcome ControlArbiter::on_disconnect(ClientId client) {
  ArbiterOutcome outcome;
  if (controller_ != client) return outcome;
  controller_.reset();
  const std::string reason = "controller " + client_name(client) + " disconnected";
  add_stop(outcome, client, reason);
  outcome.change = ControlChange{std::nullopt, client, reason};
  return outcome;
}

}  // namespace marsokhod::link
