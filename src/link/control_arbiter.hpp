// Who may drive: many clients watch, at most one holds control. Control is only ever taken
// explicitly (take_control) — a console that merely opens never drives — and taking it from
// another client is allowed, because the operator at the rover must be able to take over from
// a forgotten browser tab. Read-only clients get an error for everything that would act on the
// rover, except stop: a safety stop must work from any console, whoever holds control, and a
// stop from another console also takes control away from the holder (who pressed STOP did so
// because of what the holder's rover does). Whenever control changes hands or is given up
// (release, disconnect) the rover is stopped, so it never keeps driving on a command its new
// operator did not give; the driver then holds the stop until the controller's input is neutral
// (driver::OperatorChannel). Every stop carries its reason, and every console is told who
// stopped and why (StopNotice). Pure: no I/O, no time.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "link/operator_message.hpp"

namespace marsokhod::link {

using ClientId = std::uint64_t;

// A message for the application, already allowed by the control rules.
struct InboundCommand {
  ClientId client_id = 0;
  OperatorMessage message;
  // Why: for every stop, who stopped and why ("client 3 pressed STOP", "client 2 took control
  // from client 1"); empty for the other messages.
  std::string reason;
};

// A stop, told to every console.
struct StopNotice {
  ClientId by = 0;  // whose action stopped the rover
  std::string reason;
};

struct ControlChange {
  std::optional<ClientId> controller;  // after the change
  std::optional<ClientId> previous;    // before it
  std::string reason;                  // "client 2 took control from client 1"
};

// What one event leads to. The server sends `error` and the pong to the sender, queues `inbound`
// for the application in order, and tells every client about `change`.
struct ArbiterOutcome {
  std::vector<InboundCommand> inbound;
  std::optional<MessageError> error;
  bool pong = false;
  std::optional<ControlChange> change;
  // A take_control by the holder repeats the state to it alone: a flood of them must not be
  // re-broadcast to every console.
  bool change_to_sender_only = false;
  std::optional<StopNotice> stopped;
};

inline constexpr const char* kReadOnlyMessage = "read-only: take control first";

class ControlArbiter {
 public:
  std::optional<ClientId> controller() const { return controller_; }

  // A parsed message from `client`. Ping is answered here and never forwarded; take_control and
  // release_control are forwarded (after they took effect) for the application's log.
  ArbiterOutcome on_message(ClientId client, const OperatorMessage& message);

  // `client` is gone. If it held control: a stop, and control is free.
  ArbiterOutcome on_disconnect(ClientId client);

 private:
  ArbiterOutcome take_control(ClientId client);
  ArbiterOutcome release_control(ClientId client);
  ArbiterOutcome stop(ClientId client);

  std::optional<ClientId> controller_;
};

}  // namespace marsokhod::link
