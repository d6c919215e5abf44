#include "runner/live_console.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ostream>

#include "link/access_token.hpp"
#include "link/status_json.hpp"

namespace marsokhod::runner {
namespace {

// --token, else --token-file, else $MARSOKHOD_TOKEN, else [console] token; empty: generated.
std::string console_token(const ConsoleArgs& args, const config::ConsoleParams& config) {
  if (!args.token.empty()) return args.token;
  if (!args.token_file.empty()) return link::read_token_file(args.token_file);
  if (const char* env = std::getenv("MARSOKHOD_TOKEN"); env != nullptr && *env != '\0') return env;
  return config.token;
}

}  // namespace

LiveConsole::LiveConsole(const config::LoadedConfig& config, const ConsoleArgs& args,
                         std::ostream& out) {
  const Params& params = config.params;
  const config::ConsoleParams& c = config.console;
  const double rate_hz = args.status_rate_hz > 0.0 ? args.status_rate_hz : c.status_rate_hz;
  status_every_ = static_cast<std::uint64_t>(
      std::max(1L, std::lround(1.0 / (params.cycle.period_s * rate_hz))));
  if (args.no_console) return;
  link::ServerOptions options;
  options.listen = link::parse_listen_address(args.listen.empty() ? c.listen : args.listen);
  if (!args.web.empty()) options.static_dir = std::filesystem::path(args.web);
  options.token = console_token(args, c);
  options.allowed_hosts = c.allowed_hosts;
  options.allowed_origins = c.allowed_origins;
  options.status_period_s = 1.0 / rate_hz;
  options.calibration = config.calibration;
  server_ = std::make_unique<link::LinkServer>(params, options);
  server_->start();
  can_.emplace(params);
  out << "console: " << server_->console_url() << "\n";
  out << "foxglove: " << server_->foxglove_url() << "\n";
  if (!options.static_dir) {
    out << "note: no console build found (web/dist); run `make web` — the WebSocket still works\n";
  }
  out << std::flush;
}

link::CycleCommands LiveConsole::take(const driver::RuntimeSettings& current) {
  if (!server_) return {};
  return link::merge_cycle_commands(server_->take_inbound(), current);
}

void LiveConsole::publish(const driver::DriverStatus& status, const nlohmann::json& truth,
                          const std::optional<TruePose>& true_pose) {
  if (!server_) return;
  server_->publish_status(link::status_json(status, truth));
  const link::FoxgloveInterest interest = server_->foxglove_interest();
  if (!interest.connected) return;
  // The time message goes with every status, whether or not a channel is subscribed; the
  // messages are built the first time (to advertise them) and then while someone subscribes.
  const bool wanted = !status_channels_seen_ ||
                      std::any_of(interest.subscribed.begin(), interest.subscribed.end(),
                                  [](const std::string& topic) { return topic.rfind("/can/", 0) != 0; });
  status_channels_seen_ = true;
  send_foxglove(interest,
                wanted ? status_channel_messages(std::llround(status.mission_time_s * 1e6), &status,
                                                 truth, true_pose)
                       : std::vector<ChannelMessage>{},
                status);
}

void LiveConsole::frames(const driver::DriverStatus& status,
                         const std::vector<std::pair<std::int64_t, protocol::CanFrame>>& received,
                         const std::vector<protocol::CanFrame>& sent, std::int64_t time_us) {
  if (!server_) return;
  const link::FoxgloveInterest interest = server_->foxglove_interest();
  const auto wanted = [&](const std::string& topic) {
    return interest.connected && (interest.wants(topic) || seen_.count(topic) == 0);
  };
  // Every frame passes through the bus context, built or not.
  std::vector<ChannelMessage> messages;
  std::vector<ChannelMessage>* out =
      wanted("/can/raw") || wanted("/can/decoded") ? &messages : nullptr;
  for (const auto& [t_us, frame] : received) can_->add(t_us, frame, true, out);
  for (const protocol::CanFrame& frame : sent) can_->add(time_us, frame, false, out);
  if (!messages.empty()) send_foxglove(interest, std::move(messages), status);
}

void LiveConsole::send_foxglove(const link::FoxgloveInterest& interest,
                                std::vector<ChannelMessage> messages,
                                const driver::DriverStatus& status) {
  std::vector<link::FoxgloveMessage> chosen;
  for (ChannelMessage& m : messages) {
    const bool first = seen_.insert(m.topic).second;
    if (!first && !interest.wants(m.topic)) continue;
    std::shared_ptr<const std::string>& schema = schemas_[m.topic];
    if (!schema) {
      schema = std::make_shared<const std::string>(
          channel_schema(m.schema_name, nlohmann::json::parse(m.text)).dump());
    }
    chosen.push_back({m.topic, m.schema_name, schema, std::move(m.text)});
  }
  const double ns = std::max(0.0, status.mission_time_s) * 1e9;
  server_->publish_foxglove(static_cast<std::uint64_t>(std::llround(ns)), std::move(chosen));
}

}  // namespace marsokhod::runner
