// The console of `marsokhod run` and `marsokhod drive` (live.hpp): the link server set up from
// the command line and the configuration's [console], each cycle's commands merged by the link's
// rule (link/cycle_commands.hpp), and the status published at the status rate — to the consoles
// and, with the other channels of channel_messages.hpp, to the Foxglove clients on /foxglove
// (only the channels someone subscribes to are built, and only while one is connected).
#pragma once

#include <iosfwd>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "config/loaded_config.hpp"
#include "core/params.hpp"
#include "driver/operator_commands.hpp"
#include "driver/status.hpp"
#include "link/cycle_commands.hpp"
#include "link/link_server.hpp"
#include "runner/channel_messages.hpp"

namespace marsokhod::runner {

// Empty or zero: the configuration's [console] values.
struct ConsoleArgs {
  std::string listen;
  std::string token;            // visible to every user in `ps`: prefer token_file or the environment
  std::string token_file;       // the token in a file only its owner may read (mode 0600)
  std::string web;              // the console's build folder; empty: none (the WebSocket still works)
  bool no_console = false;
  double status_rate_hz = 0.0;
};

class LiveConsole {
 public:
  // Starts the server (unless args.no_console) and prints its address. Throws what LinkServer
  // and the token file throw: a bad address, token or file.
  LiveConsole(const config::LoadedConfig& config, const ConsoleArgs& args, std::ostream& out);

  // The commands that arrived since the last call, merged; `current`: the settings in force.
  link::CycleCommands take(const driver::RuntimeSettings& current);
  // truth: the simulator's (link::truth_json) or null; true_pose: the simulator's, for /tf.
  void publish(const driver::DriverStatus& status, const nlohmann::json& truth,
               const std::optional<TruePose>& true_pose = std::nullopt);
  // Every cycle, the frames on the bus in bus order (received: at their bus time, µs; sent: at
  // the cycle's), for /can/raw and /can/decoded; `status`: the cycle's (its mission time).
  void frames(const driver::DriverStatus& status,
              const std::vector<std::pair<std::int64_t, protocol::CanFrame>>& received,
              const std::vector<protocol::CanFrame>& sent, std::int64_t time_us);
  // The status rate in cycles: publish every this many cycles.
  std::uint64_t status_every() const { return status_every_; }

 private:
  // Hands the messages of the topics someone subscribes to (and any topic's first, which
  // advertises it) to the server, logged at the status' mission time.
  void send_foxglove(const link::FoxgloveInterest& interest, std::vector<ChannelMessage> messages,
                     const driver::DriverStatus& status);

  std::unique_ptr<link::LinkServer> server_;
  std::uint64_t status_every_ = 1;
  std::optional<CanChannels> can_;
  std::set<std::string> seen_;  // topics handed to the server at least once
  bool status_channels_seen_ = false;  // the status' channels built once (and so advertised)
  std::map<std::string, std::shared_ptr<const std::string>> schemas_;
};

}  // namespace marsokhod::runner
