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
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <nlohmann/json.hpp>

#include "link/link_server.hpp"

namespace marsokhod::link {

// Anything stop() must close so that the server thread can finish: every HTTP and WebSocket
// session registers itself while it lives.
class Connection {
 public:
  virtual ~Connection() = default;
  virtual void close() = 0;
};

class WebSocketSession;

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
  ServerStats stats() const;

  // --- the sessions' side, on the server thread only ---
  boost::asio::io_context& io() { return io_; }
  bool stopping() const { return stopping_; }
  std::uint64_t track(std::weak_ptr<Connection> connection);
  void untrack(std::uint64_t key);
  bool authorized(std::string_view target);  // counts refusals
  bool has_room() const { return clients_.size() < options_.max_clients; }
  void count_http_request();
  // A WebSocket whose handshake completed: gets its id and the hello.
  ClientId add_client(const std::shared_ptr<WebSocketSession>& session);
  void remove_client(ClientId client);
  void on_text(ClientId client, std::string_view text);
  void on_binary(ClientId client);
  void on_slow_client(ClientId client);

 private:
  void run_thread();
  void accept();
  void shutdown();
  void flush_status();
  void apply(ClientId sender, ArbiterOutcome outcome);
  bool push_inbound(std::vector<InboundCommand> commands);
  void send_to(ClientId client, const nlohmann::json& message);
  void reject(ClientId client, const MessageError& error);

  Params params_;
  ServerOptions options_;
  std::string token_;
  ControlArbiter arbiter_;
  std::map<ClientId, std::shared_ptr<WebSocketSession>> clients_;
  std::map<std::uint64_t, std::weak_ptr<Connection>> connections_;
  ClientId next_client_ = 1;
  std::uint64_t next_connection_ = 1;
  bool stopping_ = false;
  std::chrono::steady_clock::time_point next_status_time_{};

  mutable std::mutex mutex_;  // guards the four below
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
  std::thread thread_;
};

}  // namespace marsokhod::link
