// The operator console's server: HTTP for the console's files, a WebSocket at /ws for the
// protocol of docs/operator-protocol.md and one at /foxglove for Foxglove's
// (foxglove.websocket.v1: foxglove_protocol.hpp, docs/foxglove.md), on its own thread
// (Boost.Beast over Boost.Asio). The
// application's control loop never waits on the network: it takes the commands that arrived
// (take_inbound) and hands over the newest status (publish_status), both without blocking on
// any client.
//
// Safety and flow rules (docs/operator-protocol.md has them for console writers):
//  - every request's Host must be one of ours (DNS rebinding), every WebSocket upgrade's Origin
//    too (cross-site WebSocket hijacking): request_guard.hpp; others get 403;
//  - every WebSocket needs a session cookie (POST /session exchanges the token for one) or the
//    token as Authorization: Bearer; the console's files load without either; wrong tokens are
//    logged and back off per address (auth_guard.hpp);
//  - gamepad and targets messages out of order or stale (a burst after a network stall) are
//    dropped (input_freshness.hpp), and every console's message rate is limited;
//  - control rules: control_arbiter.hpp; a controller's disconnect becomes a stop at once, its
//    silence is the driver's operator_timeout_s;
//  - every queue is bounded: a client whose outgoing queue fills (it reads slower than status
//    arrives, or not at all) is dropped rather than allowed to hold memory or delay others;
//    a Foxglove client's data messages instead give way, oldest first (they are a stream);
//    when the application stops taking commands, new ones are refused with an error, except a
//    stop, which displaces the oldest command.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "config/configuration.hpp"
#include "core/params.hpp"
#include "link/control_arbiter.hpp"
#include "link/listen_address.hpp"

namespace marsokhod::link {

struct ServerOptions {
  ListenAddress listen;                             // --listen, default 127.0.0.1:8080
  std::optional<std::filesystem::path> static_dir;  // the console's build (web/dist); none: 404
  std::string token;                   // empty: generate_token(); else validate_token()
  double status_period_s = 0.05;       // at most one status per period (20 Hz), the newest
  std::size_t max_clients = 16;        // WebSocket clients at once; more get HTTP 503
  std::size_t client_queue_messages = 64;   // unsent messages per client before it is dropped
  std::size_t inbound_queue_commands = 256;  // commands waiting for take_inbound
  // Foxglove: unsent messages per client before its oldest data messages are dropped, and the
  // messages published but not yet taken by the server thread (the oldest dropped beyond).
  std::size_t foxglove_queue_messages = 1024;
  std::size_t foxglove_pending_messages = 4096;
  double idle_timeout_s = 10.0;        // a WebSocket silent this long (pings unanswered) is closed
  std::vector<std::string> allowed_hosts;    // Host names served besides the listen address
  std::vector<std::string> allowed_origins;  // WebSocket origins besides the server's own
  config::CalibrationSource calibration;     // the driver's calibration file, told in `hello`
  std::size_t max_connections = 48;    // HTTP and WebSocket at once, handshakes included
  double http_connection_max_s = 60.0;  // total keep-alive time of one HTTP connection
  double max_input_age_s = 0.25;       // gamepad/targets later than the console's others: dropped
  double message_rate_per_s = 60.0;    // per console, on average (it sends 20 Hz)...
  double message_burst = 60.0;         // ...and at once; excess dropped and counted
  double control_rate_per_s = 4.0;     // take_control, release_control, stop: the broadcasts
  double control_burst = 8.0;
  double auth_backoff_first_s = 1.0;   // an address's wait after a wrong token, doubling...
  double auth_backoff_max_s = 30.0;    // ...up to this
  // Called on the server thread with every text message before it is handled (logging, tests).
  // If it throws, that is a failed handler: the console's session is closed (a stop if it held
  // control), and the server serves on.
  std::function<void(ClientId, std::string_view)> message_observer;
};

struct ServerStats {
  std::size_t clients = 0;              // WebSocket clients connected now
  std::optional<ClientId> controller;   // who holds control
  std::uint64_t connections = 0;        // WebSocket clients accepted since start()
  std::uint64_t unauthorized = 0;       // upgrades and sessions refused: missing or wrong token
  std::uint64_t auth_throttled = 0;     // refused unseen: the address is backing off
  std::uint64_t forbidden = 0;          // 403: a Host or Origin not ours
  std::uint64_t connections_refused = 0;  // closed at once: max_connections reached
  std::uint64_t rate_limited = 0;       // messages dropped for the rate limit
  std::uint64_t stale_dropped = 0;      // gamepad/targets out of order or stale
  std::uint64_t handler_failures = 0;   // a handler threw: its session was closed
  std::uint64_t dropped_slow = 0;       // clients dropped because their queue was full
  std::uint64_t messages_received = 0;  // WebSocket messages from clients
  std::uint64_t messages_rejected = 0;  // answered with an error
  std::uint64_t inbound_refused = 0;    // refused (or displaced by a stop): the queue was full
  std::uint64_t controller_disconnects = 0;  // each became a stop
  std::uint64_t statuses_published = 0;  // publish_status calls
  std::uint64_t statuses_sent = 0;       // status broadcasts; fewer when coalesced
  std::uint64_t http_requests = 0;       // plain HTTP requests (files, refusals)
  std::size_t foxglove_clients = 0;      // Foxglove clients connected now
  std::uint64_t foxglove_connections = 0;  // Foxglove clients accepted since start()
  std::uint64_t foxglove_messages_sent = 0;     // message data sent to subscribers
  std::uint64_t foxglove_messages_dropped = 0;  // data dropped for a slow client or a full hand-over
};

// One message for the Foxglove clients (publish_foxglove): its channel by topic (advertised the
// first time it is seen, with `schema` — a JSON Schema's text — under `schema_name`), the JSON
// payload and its log time.
struct FoxgloveMessage {
  std::string topic;
  std::string schema_name;
  std::shared_ptr<const std::string> schema;
  std::string payload;
};

// What the Foxglove clients want now: whether any is connected, and the topics subscribed to.
struct FoxgloveInterest {
  bool connected = false;
  std::vector<std::string> subscribed;  // sorted, each once
  bool wants(const std::string& topic) const;
};

class ServerCore;

class LinkServer {
 public:
  // Keeps a copy of `params` (the ranges the parser checks). Throws std::invalid_argument for a
  // bad token, a status period that is negative or not finite, or zero-sized limits.
  LinkServer(const Params& params, ServerOptions options);
  ~LinkServer();  // stop()
  LinkServer(const LinkServer&) = delete;
  LinkServer& operator=(const LinkServer&) = delete;

  // Binds and starts the server thread. Throws std::runtime_error naming the address when it
  // cannot listen (in use, not a local address), std::logic_error when called twice.
  void start();
  // Closes every connection and joins the thread. Idempotent; start() cannot follow.
  void stop();

  // The bound port (the one chosen for port 0); 0 before start().
  std::uint16_t port() const;
  const std::string& token() const;
  // What to open in a browser: "http://127.0.0.1:8080/?token=…" (the page trades the token for
  // a session cookie and removes it from the address bar).
  std::string console_url() const;
  // What to give Foxglove (Open connection → Foxglove WebSocket):
  // "ws://127.0.0.1:8080/foxglove?token=…".
  std::string foxglove_url() const;

  // Thread-safe. Every command that arrived since the last call, oldest first.
  std::vector<InboundCommand> take_inbound();
  // Thread-safe, never blocks on clients: keeps `status` as the newest; the server thread sends
  // it to every client as {"type":"status","status":…} no sooner than status_period_s after the
  // previous one. Statuses published in between are replaced, never queued.
  void publish_status(nlohmann::json status);
  // Thread-safe, never blocks on clients: the Foxglove clients get a time message (`time_ns`,
  // the rover's mission time) and each message on a channel they subscribe to, logged at
  // `time_ns`. A channel is advertised the first time a message names its topic.
  void publish_foxglove(std::uint64_t time_ns, std::vector<FoxgloveMessage> messages);
  // Thread-safe: what to build messages for (nothing while no Foxglove client is connected).
  FoxgloveInterest foxglove_interest() const;
  ServerStats stats() const;

 private:
  std::unique_ptr<ServerCore> core_;
};

}  // namespace marsokhod::link
