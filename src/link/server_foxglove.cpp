// ServerCore's Foxglove side (server_core.hpp): the clients on /foxglove, the channels
// advertised to them, what they subscribe to, the parameters. On the server thread, except
// publish_foxglove and foxglove_interest (the application's thread; they only take the mutex).
#include <algorithm>
#include <cstdio>

#include <boost/asio/post.hpp>

#include "link/command_json.hpp"
#include "link/server_core.hpp"
#include "link/server_messages.hpp"
#include "link/websocket_session.hpp"

namespace marsokhod::link {
namespace {

using Json = nlohmann::json;
using foxglove::StatusLevel;

}  // namespace

bool FoxgloveInterest::wants(const std::string& topic) const {
  return std::binary_search(subscribed.begin(), subscribed.end(), topic);
}

ClientId ServerCore::add_foxglove_client(const std::shared_ptr<WebSocketSession>& session) {
  const ClientId id = next_client_++;
  FoxgloveClient& client =
      foxglove_clients_
          .emplace(id, FoxgloveClient{session, {}, {},
                                      TokenBucket(options_.message_rate_per_s,
                                                  options_.message_burst)})
          .first->second;
  {
    const std::lock_guard lock(mutex_);
    ++stats_.foxglove_connections;
    stats_.foxglove_clients = foxglove_clients_.size();
  }
  update_foxglove_interest();
  send_foxglove(client, foxglove::server_info_json("marsokhod"));
  if (!channels_.empty()) {
    std::vector<foxglove::Channel> all;
    for (const auto& [topic, channel] : channels_) all.push_back(channel);
    send_foxglove(client, foxglove::advertise_json(all));
  }
  return id;
}

void ServerCore::remove_foxglove_client(ClientId client) {
  foxglove_clients_.erase(client);
  {
    const std::lock_guard lock(mutex_);
    stats_.foxglove_clients = foxglove_clients_.size();
  }
  update_foxglove_interest();
}

void ServerCore::update_foxglove_interest() {
  std::set<std::string> topics;
  for (const auto& [id, client] : foxglove_clients_) {
    for (const auto& [subscription, channel_id] : client.subscriptions) {
      for (const auto& [topic, channel] : channels_) {
        if (channel.id == channel_id) topics.insert(topic);
      }
    }
  }
  const std::lock_guard lock(mutex_);
  foxglove_interest_.connected = !foxglove_clients_.empty();
  foxglove_interest_.subscribed.assign(topics.begin(), topics.end());
}

FoxgloveInterest ServerCore::foxglove_interest() const {
  const std::lock_guard lock(mutex_);
  return foxglove_interest_;
}

void ServerCore::send_foxglove(FoxgloveClient& client, const Json& message) {
  // A copy: a send may drop a slow client, which erases it from foxglove_clients_.
  const auto session = client.session;
  session->send_foxglove(std::make_shared<const std::string>(wire_text(message)), false, false);
}

void ServerCore::send_foxglove_status(ClientId client, StatusLevel level, const std::string& text) {
  const auto it = foxglove_clients_.find(client);
  if (it == foxglove_clients_.end()) return;
  {
    const std::lock_guard lock(mutex_);
    ++stats_.messages_rejected;
  }
  send_foxglove(it->second, foxglove::status_message(level, text));
}

void ServerCore::on_foxglove_dropped(std::uint64_t messages) {
  const std::lock_guard lock(mutex_);
  stats_.foxglove_messages_dropped += messages;
}

void ServerCore::on_foxglove_binary(ClientId client) {
  count(&ServerStats::messages_received);
  send_foxglove_status(client, StatusLevel::kError,
                       "binary messages (clientPublish, service calls) are not supported here; "
                       "this server only publishes");
}

void ServerCore::on_foxglove_text(ClientId id, std::string_view text) {
  count(&ServerStats::messages_received);
  const auto it = foxglove_clients_.find(id);
  if (it == foxglove_clients_.end()) return;
  FoxgloveClient& client = it->second;
  if (!client.messages.take(steady_now_s())) {
    count(&ServerStats::rate_limited);
    return;
  }
  if (options_.message_observer) options_.message_observer(id, text);
  const foxglove::ClientOp op = foxglove::parse_client_op(text);
  if (const auto* subscribe_op = std::get_if<foxglove::Subscribe>(&op)) {
    subscribe(client, *subscribe_op);
  } else if (const auto* unsubscribe_op = std::get_if<foxglove::Unsubscribe>(&op)) {
    unsubscribe(client, *unsubscribe_op);
  } else if (const auto* get = std::get_if<foxglove::GetParameters>(&op)) {
    get_parameters(client, *get);
  } else if (const auto* set = std::get_if<foxglove::SetParameters>(&op)) {
    set_parameters(id, client, *set);
  } else if (const auto* updates = std::get_if<foxglove::SubscribeParameterUpdates>(&op)) {
    client.parameter_updates.insert(updates->names.begin(), updates->names.end());
    if (updates->names.empty()) {  // every parameter
      for (const Json& p : foxglove::settings_parameters(settings_)) {
        client.parameter_updates.insert(p["name"].get<std::string>());
      }
    }
  } else if (const auto* no_updates = std::get_if<foxglove::UnsubscribeParameterUpdates>(&op)) {
    for (const std::string& name : no_updates->names) client.parameter_updates.erase(name);
  } else {
    send_foxglove_status(id, StatusLevel::kError, std::get<foxglove::FoxgloveError>(op).message);
  }
}

void ServerCore::subscribe(FoxgloveClient& client, const foxglove::Subscribe& op) {
  std::string refused;
  for (const auto& [subscription, channel_id] : op.subscriptions) {
    const std::uint32_t wanted = channel_id;  // clang 14 cannot capture a structured binding
    const bool known = std::any_of(channels_.begin(), channels_.end(), [&](const auto& entry) {
      return entry.second.id == wanted;
    });
    if (!known) {
      refused += (refused.empty() ? "" : "; ") + std::string("channel ") +
                 std::to_string(channel_id) + " is not advertised";
    } else if (client.subscriptions.count(subscription) != 0) {
      refused += (refused.empty() ? "" : "; ") + std::string("subscription id ") +
                 std::to_string(subscription) + " is in use";
    } else {
      client.subscriptions.emplace(subscription, channel_id);
    }
  }
  update_foxglove_interest();
  if (!refused.empty()) {
    send_foxglove(client, foxglove::status_message(StatusLevel::kError, "subscribe: " + refused));
  }
}

void ServerCore::unsubscribe(FoxgloveClient& client, const foxglove::Unsubscribe& op) {
  std::string unknown;
  for (const std::uint32_t subscription : op.subscription_ids) {
    if (client.subscriptions.erase(subscription) == 0) {
      unknown += (unknown.empty() ? "" : ", ") + std::to_string(subscription);
    }
  }
  update_foxglove_interest();
  if (!unknown.empty()) {
    send_foxglove(client, foxglove::status_message(
                              StatusLevel::kWarning, "unsubscribe: no subscription " + unknown));
  }
}

void ServerCore::get_parameters(FoxgloveClient& client, const foxglove::GetParameters& op) {
  Json all = foxglove::settings_parameters(settings_);
  Json out = Json::array();
  std::string unknown;
  for (const std::string& name : op.names) {
    const auto it = std::find_if(all.begin(), all.end(),
                                 [&](const Json& p) { return p["name"] == name; });
    if (it == all.end()) {
      unknown += (unknown.empty() ? "" : ", ") + name;
    } else {
      out.push_back(*it);
    }
  }
  if (op.names.empty()) out = all;
  send_foxglove(client, foxglove::parameter_values_json(out, op.id));
  if (!unknown.empty()) {
    send_foxglove(client,
                  foxglove::status_message(StatusLevel::kWarning,
                                           settings_.is_null()
                                               ? "getParameters: no status from the rover yet"
                                               : "getParameters: no parameter " + unknown));
  }
}

void ServerCore::set_parameters(ClientId id, FoxgloveClient& client,
                                const foxglove::SetParameters& op) {
  const auto configure = foxglove::configure_of(op.parameters, params_);
  if (const auto* error = std::get_if<foxglove::FoxgloveError>(&configure)) {
    send_foxglove_status(id, StatusLevel::kError, error->message);
    return;
  }
  // The control rules decide, as for a console's configure: only the client holding control.
  ArbiterOutcome outcome = arbiter_.on_message(id, std::get<ConfigureMessage>(configure));
  if (outcome.error) {
    send_foxglove_status(
        id, StatusLevel::kError,
        "setParameters: " + outcome.error->message +
            " — only the console holding control changes the settings (a Foxglove client "
            "cannot take control; change them in the console)");
    return;
  }
  if (!outcome.inbound.empty() && !push_inbound(std::move(outcome.inbound))) {
    send_foxglove_status(id, StatusLevel::kError,
                         "setParameters: the rover is not taking commands (queue full)");
    return;
  }
  if (op.id) {
    // The values the driver takes at its next cycle.
    const auto& change = std::get<ConfigureMessage>(configure).change;
    Json current = settings_.is_object() ? settings_ : Json::object();
    const Json applied = runtime_settings_json(change.applied_to(
        runtime_settings_from_json(current, driver::RuntimeSettings{})));
    send_foxglove(client, foxglove::parameter_values_json(
                              foxglove::settings_parameters(applied), op.id));
  }
}

// The newest status' settings: the clients that asked for updates hear the parameters that
// changed.
void ServerCore::foxglove_settings(const Json& settings) {
  if (settings == settings_) return;
  const Json before = foxglove::settings_parameters(settings_);
  settings_ = settings;
  const Json after = foxglove::settings_parameters(settings_);
  for (auto& [id, client] : foxglove_clients_) {
    Json changed = Json::array();
    for (const Json& p : after) {
      if (client.parameter_updates.count(p["name"].get<std::string>()) == 0) continue;
      if (std::find(before.begin(), before.end(), p) == before.end()) changed.push_back(p);
    }
    if (!changed.empty()) send_foxglove(client, foxglove::parameter_values_json(changed));
  }
}

void ServerCore::publish_foxglove(std::uint64_t time_ns, std::vector<FoxgloveMessage> messages) {
  {
    const std::lock_guard lock(mutex_);
    foxglove_pending_messages_ += messages.size();
    foxglove_pending_.push_back({time_ns, std::move(messages)});
    // Bounded: the server thread fell behind; the oldest batches give way.
    while (foxglove_pending_.size() > 1 &&
           foxglove_pending_messages_ > options_.foxglove_pending_messages) {
      foxglove_pending_messages_ -= foxglove_pending_.front().messages.size();
      stats_.foxglove_messages_dropped += foxglove_pending_.front().messages.size();
      foxglove_pending_.pop_front();
    }
    if (foxglove_flush_posted_) return;
    foxglove_flush_posted_ = true;
  }
  boost::asio::post(io_, [this] { flush_foxglove(); });
}

void ServerCore::flush_foxglove() {
  std::deque<FoxgloveBatch> batches;
  {
    const std::lock_guard lock(mutex_);
    batches.swap(foxglove_pending_);
    foxglove_pending_messages_ = 0;
    foxglove_flush_posted_ = false;
  }
  if (stopping_) return;
  std::uint64_t sent = 0;
  for (FoxgloveBatch& batch : batches) {
    std::vector<foxglove::Channel> added;
    for (const FoxgloveMessage& m : batch.messages) {
      if (channels_.count(m.topic) != 0 || !m.schema) continue;
      const auto id = static_cast<std::uint32_t>(channels_.size() + 1);
      added.push_back(channels_[m.topic] = {id, m.topic, m.schema_name, *m.schema});
    }
    // Copies: a send may drop a slow client, which erases it from foxglove_clients_.
    std::vector<std::pair<std::shared_ptr<WebSocketSession>, std::map<std::uint32_t, std::uint32_t>>>
        clients;
    for (const auto& [id, client] : foxglove_clients_) {
      clients.emplace_back(client.session, client.subscriptions);
    }
    const auto time = std::make_shared<const std::string>(foxglove::time_message(batch.time_ns));
    const auto advertise =
        added.empty() ? nullptr
                      : std::make_shared<const std::string>(
                            wire_text(foxglove::advertise_json(added)));
    for (const auto& [session, subscriptions] : clients) {
      if (advertise) session->send_foxglove(advertise, false, false);
      session->send_foxglove(time, true, true);
      for (const auto& [subscription, channel_id] : subscriptions) {
        for (const FoxgloveMessage& m : batch.messages) {
          const auto it = channels_.find(m.topic);
          if (it == channels_.end() || it->second.id != channel_id) continue;
          session->send_foxglove(std::make_shared<const std::string>(foxglove::message_data(
                                     subscription, batch.time_ns, m.payload)),
                                 true, true);
          ++sent;
        }
      }
    }
  }
  const std::lock_guard lock(mutex_);
  stats_.foxglove_messages_sent += sent;
}

}  // namespace marsokhod::link
