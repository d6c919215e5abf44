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
  out << "console: " << server_->console_url() << "\n";
  if (!options.static_dir) {
    out << "note: no console build found (web/dist); run `make web` — the WebSocket still works\n";
  }
  out << std::flush;
}

link::CycleCommands LiveConsole::take(const driver::RuntimeSettings& current) {
  if (!server_) return {};
  return link::merge_cycle_commands(server_->take_inbound(), current);
}

void LiveConsole::publish(const driver::DriverStatus& status, const nlohmann::json& truth) {
  if (server_) server_->publish_status(link::status_json(status, truth));
}

}  // namespace marsokhod::runner
