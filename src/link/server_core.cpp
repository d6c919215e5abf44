#include "link/server_core.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <stdexcept>

#include <boost/asio/ip/address.hpp>
#include <boost/asio/post.hpp>

#include "link/access_token.hpp"
#include "link/http_session.hpp"
#include "link/server_messages.hpp"
#include "link/websocket_session.hpp"

namespace marsokhod::link {
namespace {

namespace asio = boost::asio;
using tcp = asio::ip::tcp;

void validate(const ServerOptions& options) {
  parse_listen_address(to_string(options.listen));  // throws naming the address
  if (!std::isfinite(options.status_period_s) || options.status_period_s < 0.0) {
    throw std::invalid_argument("status_period_s: must be a finite number ≥ 0 s");
  }
  if (!std::isfinite(options.idle_timeout_s) || options.idle_timeout_s <= 0.0) {
    throw std::invalid_argument("idle_timeout_s: must be a finite number > 0 s");
  }
  if (options.max_clients == 0 || options.client_queue_messages == 0 ||
      options.inbound_queue_commands == 0 || options.max_connections == 0 ||
      options.foxglove_queue_messages == 0 || options.foxglove_pending_messages == 0) {
    throw std::invalid_argument(
        "max_clients, client_queue_messages, inbound_queue_commands, max_connections, "
        "foxglove_queue_messages, foxglove_pending_messages: must be at least 1");
  }
  for (const double value :
       {options.http_connection_max_s, options.max_input_age_s, options.message_rate_per_s,
        options.message_burst, options.control_rate_per_s, options.control_burst,
        options.auth_backoff_first_s, options.auth_backoff_max_s}) {
    if (!std::isfinite(value) || value <= 0.0) {
      throw std::invalid_argument(
          "http_connection_max_s, max_input_age_s, the rates, bursts and back-offs: must be "
          "finite numbers > 0");
    }
  }
  for (const std::string& host : options.allowed_hosts) validate_host_name(host);
  for (const std::string& origin : options.allowed_origins) validate_origin(origin);
}

// Back off after a failed accept (out of file descriptors): retrying at once would spin.
constexpr auto kAcceptRetry = std::chrono::milliseconds(100);
constexpr std::size_t kMaxThrottledAddresses = 1024;

std::string checked_token(const std::string& given) {
  if (given.empty()) return generate_token();
  validate_token(given);
  return given;
}

}  // namespace

ServerCore::ServerCore(const Params& params, ServerOptions options)
    : params_(params),
      options_(std::move(options)),
      token_(checked_token(options_.token)),
      throttle_(options_.auth_backoff_first_s, options_.auth_backoff_max_s,
                kMaxThrottledAddresses),
      acceptor_(io_),
      status_timer_(io_),
      accept_timer_(io_) {
  validate(options_);
}

ServerCore::~ServerCore() { stop(); }

void ServerCore::start() {
  if (started_) throw std::logic_error("LinkServer::start: a server starts once");
  started_ = true;
  const tcp::endpoint endpoint(asio::ip::make_address(options_.listen.address),
                               options_.listen.port);
  boost::system::error_code error;
  acceptor_.open(endpoint.protocol(), error);
  // A restarted rover must get its port back at once, not after TIME_WAIT.
  if (!error) acceptor_.set_option(asio::socket_base::reuse_address(true), error);
  if (!error) acceptor_.bind(endpoint, error);
  if (!error) acceptor_.listen(asio::socket_base::max_listen_connections, error);
  if (error) {
    stopped_ = true;
    throw std::runtime_error("cannot listen on " + to_string(options_.listen) + ": " +
                             error.message() + "; choose another with --listen ADDR:PORT");
  }
  port_ = acceptor_.local_endpoint().port();
  policy_ = origin_policy(options_.listen.address, port_, options_.allowed_hosts,
                          options_.allowed_origins);
  accept();
  thread_ = std::thread([this] { run_thread(); });
}

void ServerCore::run_thread() {
  for (;;) {
    try {
      io_.run();
      return;
    } catch (const std::exception& error) {
      // One failed handler must not take the operator's link down with it.
      std::fprintf(stderr, "link: a server handler failed (%s); serving on\n", error.what());
    }
  }
}

void ServerCore::stop() {
  if (stopped_) return;
  stopped_ = true;
  if (!started_) return;
  asio::post(io_, [this] { shutdown(); });
  thread_.join();
}

void ServerCore::shutdown() {
  stopping_ = true;
  boost::system::error_code ignored;
  acceptor_.close(ignored);
  status_timer_.cancel();
  accept_timer_.cancel();
  std::vector<std::shared_ptr<Connection>> open;
  for (const auto& [key, connection] : connections_) {
    if (auto alive = connection.lock()) open.push_back(std::move(alive));
  }
  for (const auto& connection : open) connection->close();
}

void ServerCore::accept() {
  acceptor_.async_accept([this](boost::system::error_code error, tcp::socket socket) {
    if (stopping_ || !acceptor_.is_open()) return;
    if (error) {
      std::fprintf(stderr, "link: accept failed (%s); retrying in 100 ms\n",
                   error.message().c_str());
      accept_timer_.expires_after(kAcceptRetry);
      accept_timer_.async_wait([this](boost::system::error_code e) {
        if (!e && !stopping_) accept();
      });
      return;
    }
    if (connections_.size() >= options_.max_connections) {
      count(&ServerStats::connections_refused);  // closed unread: the socket goes at once
    } else {
      try {
        std::make_shared<HttpSession>(std::move(socket), *this)->run();
      } catch (const std::exception& e) {
        on_handler_failure("accept", e);  // e.g. the peer left before we asked its address
      }
    }
    accept();
  });
}

std::uint64_t ServerCore::track(std::weak_ptr<Connection> connection) {
  const std::uint64_t key = next_connection_++;
  connections_.emplace(key, std::move(connection));
  return key;
}

void ServerCore::untrack(std::uint64_t key) { connections_.erase(key); }

void ServerCore::count(std::uint64_t ServerStats::*counter) {
  const std::lock_guard lock(mutex_);
  ++(stats_.*counter);
}

void ServerCore::count_http_request() {
  const std::lock_guard lock(mutex_);
  ++stats_.http_requests;
}

ClientId ServerCore::add_client(const std::shared_ptr<WebSocketSession>& session) {
  const ClientId client = next_client_++;
  clients_.emplace(client, Client{session, InputFreshness(options_.max_input_age_s),
                                  TokenBucket(options_.message_rate_per_s, options_.message_burst),
                                  TokenBucket(options_.control_rate_per_s, options_.control_burst)});
  {
    const std::lock_guard lock(mutex_);
    ++stats_.connections;
    stats_.clients = clients_.size();
  }
  send_to(client, hello_json(client, arbiter_.controller(), options_.calibration,
                                  velocity_limits(params_)));
  return client;
}

void ServerCore::remove_client(ClientId client) {
  clients_.erase(client);
  ArbiterOutcome outcome = arbiter_.on_disconnect(client);
  {
    const std::lock_guard lock(mutex_);
    stats_.clients = clients_.size();
    if (outcome.change) ++stats_.controller_disconnects;
  }
  apply(client, std::move(outcome));
}

void ServerCore::on_text(ClientId client, std::string_view text) {
  count(&ServerStats::messages_received);
  const auto it = clients_.find(client);
  if (it == clients_.end()) return;
  const double now_s = steady_now_s();
  if (!it->second.messages.take(now_s)) {
    count(&ServerStats::rate_limited);
    return;
  }
  if (options_.message_observer) options_.message_observer(client, text);
  const ParseResult parsed = parse_operator_message(text, params_);
  const std::optional<OperatorMessage> message = message_of(parsed);
  if (!message) {
    reject(client, std::get<MessageError>(parsed));
    return;
  }
  ArbiterOutcome outcome;
  if (admit(*message, now_s, outcome, client)) apply(client, std::move(outcome));
}

// The per-console guards, then the arbiter. False: dropped (counted, nothing to send).
bool ServerCore::admit(const OperatorMessage& message, double now_s, ArbiterOutcome& outcome,
                       ClientId client) {
  Client& state = clients_.at(client);
  if (const auto stamp = input_stamp(message)) {
    if (state.freshness.check(*stamp, now_s)) {
      count(&ServerStats::stale_dropped);
      return false;
    }
  }
  const bool is_stop = std::holds_alternative<StopMessage>(message);
  const bool changes_control = std::holds_alternative<TakeControlMessage>(message) ||
                               std::holds_alternative<ReleaseControlMessage>(message);
  const bool within_control_rate = (!is_stop && !changes_control) || state.control.take(now_s);
  if (!within_control_rate) {
    count(&ServerStats::rate_limited);
    if (changes_control) return false;
  }
  outcome = arbiter_.on_message(client, message);
  // Over the rate, a stop still reaches the driver; only its broadcast is left out.
  if (!within_control_rate) outcome.stopped.reset();
  return true;
}

void ServerCore::on_binary(ClientId client) {
  count(&ServerStats::messages_received);
  reject(client, {"json", "binary frame: send each message as JSON text"});
}

void ServerCore::on_slow_client(ClientId client) {
  const std::lock_guard lock(mutex_);
  ++stats_.dropped_slow;
  std::fprintf(stderr, "link: client %llu dropped: it does not read fast enough\n",
               static_cast<unsigned long long>(client));
}

void ServerCore::apply(ClientId sender, ArbiterOutcome outcome) {
  if (outcome.error) reject(sender, *outcome.error);
  if (outcome.pong) send_to(sender, pong_json());
  if (!outcome.inbound.empty() && !push_inbound(std::move(outcome.inbound))) {
    reject(sender, {"type", "the rover is not taking commands (queue full); try again"});
  }
  if (outcome.change) {
    {
      const std::lock_guard lock(mutex_);
      stats_.controller = outcome.change->controller;
    }
    if (outcome.change_to_sender_only) {
      send_to(sender, control_json(*outcome.change, sender));
    } else {
      for (const auto& [client, state] : clients_) {
        send_to(client, control_json(*outcome.change, client));
      }
    }
  }
  if (outcome.stopped) {
    const auto text = std::make_shared<const std::string>(wire_text(stopped_json(*outcome.stopped)));
    // A copy: a send may drop a slow client, which erases it from clients_.
    std::vector<std::shared_ptr<WebSocketSession>> sessions;
    for (const auto& [client, state] : clients_) sessions.push_back(state.session);
    for (const auto& session : sessions) session->send(text);
  }
}

bool ServerCore::push_inbound(std::vector<InboundCommand> commands) {
  const std::lock_guard lock(mutex_);
  const bool has_stop = std::any_of(commands.begin(), commands.end(), [](const auto& command) {
    return std::holds_alternative<StopMessage>(command.message);
  });
  const std::size_t capacity = options_.inbound_queue_commands;
  if (inbound_.size() + commands.size() > capacity) {
    ++stats_.inbound_refused;
    if (!has_stop) return false;
    // A stop must get through: older commands make room (the stop overrides them anyway).
    while (!inbound_.empty() && inbound_.size() + commands.size() > capacity) inbound_.pop_front();
  }
  for (auto& command : commands) inbound_.push_back(std::move(command));
  return true;
}

void ServerCore::send_to(ClientId client, const nlohmann::json& message) {
  const auto it = clients_.find(client);
  if (it == clients_.end()) return;
  const auto session = it->second.session;  // send may drop the client, erasing the entry
  session->send(std::make_shared<const std::string>(wire_text(message)));
}

void ServerCore::reject(ClientId client, const MessageError& error) {
  {
    const std::lock_guard lock(mutex_);
    ++stats_.messages_rejected;
  }
  send_to(client, error_json(error));
}

std::vector<InboundCommand> ServerCore::take_inbound() {
  const std::lock_guard lock(mutex_);
  std::vector<InboundCommand> out(std::make_move_iterator(inbound_.begin()),
                                  std::make_move_iterator(inbound_.end()));
  inbound_.clear();
  return out;
}

ServerStats ServerCore::stats() const {
  const std::lock_guard lock(mutex_);
  return stats_;
}

void ServerCore::publish_status(nlohmann::json status) {
  {
    const std::lock_guard lock(mutex_);
    // The soil's patch (truth.soil, the 3-D view's ruts) goes with one status a second: a newer
    // status that replaces an unsent one without a patch of its own takes the patch along.
    if (pending_status_ && status.contains("truth") && status["truth"].is_object() &&
        !status["truth"].contains("soil")) {
      nlohmann::json& unsent = *pending_status_;
      if (unsent.contains("truth") && unsent["truth"].is_object() &&
          unsent["truth"].contains("soil")) {
        status["truth"]["soil"] = std::move(unsent["truth"]["soil"]);
      }
    }
    pending_status_ = std::move(status);
    ++stats_.statuses_published;
    if (status_flush_posted_) return;  // the flush on its way will take this one
    status_flush_posted_ = true;
  }
  asio::post(io_, [this] { flush_status(); });
}

void ServerCore::flush_status() {
  if (stopping_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now < next_status_time_) {
    status_timer_.expires_at(next_status_time_);
    status_timer_.async_wait([this](boost::system::error_code error) {
      if (!error) flush_status();
    });
    return;
  }
  nlohmann::json status;
  {
    const std::lock_guard lock(mutex_);
    status = std::move(*pending_status_);
    pending_status_.reset();
    status_flush_posted_ = false;
    ++stats_.statuses_sent;
  }
  next_status_time_ = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                std::chrono::duration<double>(options_.status_period_s));
  if (const auto it = status.find("settings"); it != status.end()) foxglove_settings(*it);
  // One text for every client: the dump is the expensive part.
  const auto text = std::make_shared<const std::string>(wire_text(status_envelope(status)));
  std::vector<std::shared_ptr<WebSocketSession>> sessions;
  for (const auto& [client, state] : clients_) sessions.push_back(state.session);
  for (const auto& session : sessions) session->send(text);
}

}  // namespace marsokhod::link
