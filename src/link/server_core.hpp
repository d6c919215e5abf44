// LinkServer's inside (link_server.hpp is the interface): the io_context and its thread, the
// acceptor, the clients and the control arbiter — all touched only on the server thread — and
// the two hand-over points to the application, the inbound queue and the newest status, which
// a mutex guards. Included only by the link's own .cpp files: it brings in Boost.Beast.
#pragma once

#include <chrono>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <nlohmann/json.hpp>

#include "link/auth_guard.hpp"
#include "link/foxglove_protocol.hpp"
#include "link/input_freshness.hpp"
#include "link/link_server.hpp"
#include "link/request_guard.hpp"

namespace marsokhod::link {

// Anything stop() must close so that the server thread can finish: every HTTP and WebSocket
// session registers itself while it lives.
class Connection {
 public:
  virtual ~Connection() = default;
  virtual void close() = 0;
};

class WebSocketSession;

// The steady clock in seconds: the rate limits' and back-offs' time.
double steady_now_s();

// What an authorisation check decided (HttpSession answers 401 or 429 for the refusals).
struct AuthDecision {
  enum class Result { kAllowed, kWrongToken, kBackingOff } result = Result::kWrongToken;
  double wait_s = 0.0;  // kBackingOff: how long the address must still wait
};

class ServerCore {
 public:
  ServerCore(const Params& params, ServerOptions options);
  ~ServerCore();
  ServerCore(const ServerCore&) = delete;
  ServerCore& operator=(const ServerCore&) = delete;

  void start();
  void stop();
  std::uint16_t port() const { return port_; }
  const std::string& token() const { return token_; }
  const ServerOptions& options() const { return options_; }
  std::vector<InboundCommand> take_inbound();
  void publish_status(nlohmann::json status);
  void publish_foxglove(std::uint64_t time_ns, std::vector<FoxgloveMessage> messages);
  FoxgloveInterest foxglove_interest() const;
  ServerStats stats() const;

  // --- the sessions' side, on the server thread only ---
  boost::asio::io_context& io() { return io_; }
  bool stopping() const { return stopping_; }
  std::uint64_t track(std::weak_ptr<Connection> connection);
  void untrack(std::uint64_t key);
  // Host and Origin (request_guard.hpp); count the refusals. An absent Origin passes.
  bool host_allowed(std::string_view host);
  bool origin_allowed(std::optional<std::string_view> origin);
  // A WebSocket upgrade: the session cookie, else Authorization: Bearer TOKEN, else (`query_token`,
  // Foxglove's: its connection dialog takes a URL only) ?token=TOKEN (throttled).
  AuthDecision authorize_upgrade(std::string_view cookie_header, std::string_view authorization,
                                 const std::string& address,
                                 std::optional<std::string_view> query_token = std::nullopt);
  // POST /session: the token for a new session id (set as the cookie).
  AuthDecision open_session(std::string_view authorization, const std::string& address,
                            std::string& session_id);
  std::string cookie_name() const { return "marsokhod_session_" + std::to_string(port_); }
  bool has_room() const {
    return clients_.size() + foxglove_clients_.size() < options_.max_clients;
  }
  // A handler threw: logs it; the session closes itself (and a controller's close is a stop).
  void on_handler_failure(const char* where, const std::exception& error);
  void count_http_request();
  // A WebSocket whose handshake completed: gets its id and the hello.
  ClientId add_client(const std::shared_ptr<WebSocketSession>& session);
  void remove_client(ClientId client);
  void on_text(ClientId client, std::string_view text);
  void on_binary(ClientId client);
  void on_slow_client(ClientId client);
  // The same for a Foxglove client (server_foxglove.cpp): serverInfo and the channels on connect,
  // its operations, its end.
  ClientId add_foxglove_client(const std::shared_ptr<WebSocketSession>& session);
  void remove_foxglove_client(ClientId client);
  void on_foxglove_text(ClientId client, std::string_view text);
  void on_foxglove_binary(ClientId client);
  void on_foxglove_dropped(std::uint64_t messages);

 private:
  void run_thread();
  void accept();
  void shutdown();
  void flush_status();
  void apply(ClientId sender, ArbiterOutcome outcome);
  bool push_inbound(std::vector<InboundCommand> commands);
  void send_to(ClientId client, const nlohmann::json& message);
  void reject(ClientId client, const MessageError& error);
  AuthDecision check_token(std::string_view given, const std::string& address);
  void count(std::uint64_t ServerStats::*counter);
  bool admit(const OperatorMessage& message, double now_s, ArbiterOutcome& outcome,
             ClientId client);
  // Foxglove (server_foxglove.cpp).
  struct FoxgloveClient;
  void flush_foxglove();
  void send_foxglove(FoxgloveClient& client, const nlohmann::json& message);
  void send_foxglove_status(ClientId client, foxglove::StatusLevel level, const std::string& text);
  void foxglove_settings(const nlohmann::json& settings);
  void update_foxglove_interest();
  void subscribe(FoxgloveClient& client, const foxglove::Subscribe& op);
  void unsubscribe(FoxgloveClient& client, const foxglove::Unsubscribe& op);
  void get_parameters(FoxgloveClient& client, const foxglove::GetParameters& op);
  void set_parameters(ClientId id, FoxgloveClient& client, const foxglove::SetParameters& op);

  // One console: its session and the guards on what it sends.
  struct Client {
    std::shared_ptr<WebSocketSession> session;
    InputFreshness freshness;
    TokenBucket messages;
    TokenBucket control;
  };

  // One Foxglove client: its session, its subscriptions (id → channel id), the parameters whose
  // updates it wants, and the same message-rate guard as a console's.
  struct FoxgloveClient {
    std::shared_ptr<WebSocketSession> session;
    std::map<std::uint32_t, std::uint32_t> subscriptions;
    std::set<std::string> parameter_updates;
    TokenBucket messages;
  };
  // A published batch waiting for the server thread.
  struct FoxgloveBatch {
    std::uint64_t time_ns = 0;
    std::vector<FoxgloveMessage> messages;
  };

  Params params_;
  ServerOptions options_;
  std::string token_;
  ControlArbiter arbiter_;
  std::map<ClientId, Client> clients_;
  std::map<ClientId, FoxgloveClient> foxglove_clients_;
  std::map<std::string, foxglove::Channel> channels_;  // by topic; ids from 1
  nlohmann::json settings_;  // the newest status' settings (null before the first status)
  OriginPolicy policy_;       // set by start(), once the port is known
  SessionStore sessions_{64};
  AuthThrottle throttle_;
  std::map<std::uint64_t, std::weak_ptr<Connection>> connections_;
  ClientId next_client_ = 1;
  std::uint64_t next_connection_ = 1;
  bool stopping_ = false;
  std::chrono::steady_clock::time_point next_status_time_{};

  mutable std::mutex mutex_;  // guards the members below, down to stats_
  std::deque<FoxgloveBatch> foxglove_pending_;
  std::size_t foxglove_pending_messages_ = 0;
  bool foxglove_flush_posted_ = false;
  FoxgloveInterest foxglove_interest_;
  std::deque<InboundCommand> inbound_;
  std::optional<nlohmann::json> pending_status_;
  bool status_flush_posted_ = false;
  ServerStats stats_;

  std::uint16_t port_ = 0;  // written by start() before the thread exists
  bool started_ = false;    // the application's thread only
  bool stopped_ = false;

  // Declared after everything a session touches from its destructor: the io_context destroys
  // any handlers (and with them sessions) still queued when it goes.
  boost::asio::io_context io_;
  boost::asio::ip::tcp::acceptor acceptor_;
  boost::asio::steady_timer status_timer_;
  boost::asio::steady_timer accept_timer_;  // the pause after a failed accept (EMFILE)
  std::thread thread_;
};

}  // namespace marsokhod::link
