#include "app/live_commands.hpp"

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstdio>
#include <memory>
#include <mutex>
#include <ostream>
#include <thread>

#include "bus/socketcand_server.hpp"
#include "bus/transport.hpp"
#include "link/access_token.hpp"
#include "link/link_server.hpp"
#include "link/operator_message.hpp"
#include "link/status_json.hpp"
#include "runner/recorder.hpp"
#include "runner/scenario.hpp"
#include "runner/scenario_runner.hpp"
#include "runner/session.hpp"

namespace marsokhod::app {
namespace {

using Clock = std::chrono::steady_clock;
constexpr int kUsageError = 2;

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop = true; }

void install_signal_handlers() {
  g_stop = false;
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

// The 3-D view's truth (docs/console.md).
nlohmann::json truth_json(const sim::SimulatedRover& rover) {
  const sim::GroundTruth t = rover.truth();
  nlohmann::json wheels = nlohmann::json::array();
  for (const auto& w : t.wheel_position_m) wheels.push_back(w);
  return {{"position_m", t.position_m},
          {"roll_pitch_yaw_rad", t.roll_pitch_yaw_rad},
          {"velocity_mps", t.velocity_mps},
          {"joint_angle_rad", t.joint_angle_rad},
          {"wheel_angle_rad", std::vector<double>(t.joint_angle_rad.begin(), t.joint_angle_rad.begin() + 6)},
          {"wheel_position_m", wheels},
          {"wheel_slip_mps", t.wheel_slip_mps},
          {"supply_v", rover.electrics().supply_v},
          {"computer_on", rover.computer_on()}};
}

void print_status_line(double t, const driver::DriverStatus& s, std::ostream& out) {
  char line[256];
  std::snprintf(line, sizeof line,
                "t=%7.1fs %-11s U=%5.2fV (%5.2f) D=%.2f v1=%+.2f v2=%+.2f p6=%+.3f p7=%+.3f %s%s\n", t,
                driver::mode_name(s.mode), s.supply_v, s.reference_supply_v, s.max_duty,
                s.commands.v1_radps, s.commands.v2_radps, s.motors[kFrontJoint].position_rad,
                s.motors[kRearJoint].position_rad, s.operator_timeout ? "timeout " : "",
                s.faults.empty() ? "" : s.faults.front().c_str());
  out << line << std::flush;
}

// --token, else --token-file, else $MARSOKHOD_TOKEN, else [console] token; empty: generated.
std::string console_token(const ConsoleArgs& args, const ConsoleParams& config) {
  if (!args.token.empty()) return args.token;
  if (!args.token_file.empty()) return link::read_token_file(args.token_file);
  if (const char* env = std::getenv("MARSOKHOD_TOKEN"); env != nullptr && *env != '\0') return env;
  return config.token;
}

// The console's commands of one cycle: the newest operator input (a stop wins the cycle) and
// configuration changes.
class ConsoleLink {
 public:
  ConsoleLink(const Params& params, const ConsoleArgs& args, std::ostream& out) : params_(&params) {
    if (args.no_console) return;
    link::ServerOptions options;
    const ConsoleParams& c = params.console;
    options.listen = link::parse_listen_address(args.listen.empty() ? c.listen : args.listen);
    options.static_dir = find_web_dist(args.web);
    options.token = console_token(args, c);
    options.allowed_hosts = c.allowed_hosts;
    options.allowed_origins = c.allowed_origins;
    options.status_period_s = 1.0 / (args.status_rate_hz > 0.0 ? args.status_rate_hz : c.status_rate_hz);
    server_ = std::make_unique<link::LinkServer>(params, options);
    server_->start();
    out << "console: " << server_->console_url() << "\n";
    if (!options.static_dir) {
      out << "note: no console build found (web/dist); run `make web` — the WebSocket still works\n";
    }
    out << std::flush;
  }

  std::optional<driver::OperatorInput> poll(driver::RuntimeSettings& settings, bool& changed) {
    std::optional<driver::OperatorInput> input;
    if (!server_) return input;
    for (const link::InboundCommand& command : server_->take_inbound()) {
      if (const auto* c = std::get_if<link::ConfigureMessage>(&command.message)) {
        settings = c->change.applied_to(settings);
        changed = true;
        continue;
      }
      auto next = link::operator_input(command.message);
      if (!next) continue;
      if (next->stop) next->stop_reason = command.reason;  // shown until the operator re-arms
      if (input && input->stop && !next->stop) continue;  // a stop holds for its cycle
      input = next;
    }
    return input;
  }

  void publish(const driver::DriverStatus& status, const nlohmann::json& truth) {
    if (server_) server_->publish_status(link::status_json(status, truth));
  }

 private:
  const Params* params_;
  std::unique_ptr<link::LinkServer> server_;
};

sim::SimOptions sim_options(const std::string& scenario, std::uint64_t seed,
                            std::optional<runner::Scenario>& loaded) {
  sim::SimOptions options;
  if (!scenario.empty()) {
    loaded = runner::load_scenario(scenario);
    options = loaded->sim;
  }
  options.seed = seed;
  return options;
}

}  // namespace

std::optional<std::filesystem::path> find_web_dist(const std::string& given) {
  std::error_code ec;
  if (!given.empty()) return std::filesystem::path(given);
  if (std::filesystem::is_regular_file("web/dist/index.html", ec)) return std::filesystem::path("web/dist");
  const auto tree = std::filesystem::path(MARSOKHOD_SOURCE_DIR) / "web" / "dist";
  if (std::filesystem::is_regular_file(tree / "index.html", ec)) return tree;
  return std::nullopt;
}

int run_live(const RunArgs& args, const LoadedConfig& config, std::ostream& out,
             std::ostream& err) {
  const Params& params = config.params;
  std::optional<runner::Scenario> scenario;
  std::unique_ptr<runner::Session> session;
  std::unique_ptr<ConsoleLink> console;
  std::unique_ptr<runner::Recorder> recorder;
  try {
    session = std::make_unique<runner::Session>(config.nominal, params,
                                                sim_options(args.scenario, args.seed, scenario));
    console = std::make_unique<ConsoleLink>(params, args.console, out);
    if (!args.record.empty()) {
      recorder = std::make_unique<runner::Recorder>(args.record, config.config_file,
                                                    config.calibration_file);
    }
  } catch (const std::exception& e) {
    err << "marsokhod run: " << e.what() << "\n";
    return kUsageError;
  }
  out << describe_calibration(params) << "\n";
  install_signal_handlers();
  const auto start = Clock::now();
  const auto period = std::chrono::microseconds(session->cycle_us());
  const double rate_hz = args.console.status_rate_hz > 0.0 ? args.console.status_rate_hz
                                                           : params.console.status_rate_hz;
  const int status_every =
      std::max(1, static_cast<int>(std::lround(1.0 / (params.cycle.period_s * rate_hz))));
  std::size_t next_fault = 0;
  for (std::uint64_t k = 0; !g_stop; ++k) {
    std::this_thread::sleep_until(start + period * static_cast<std::int64_t>(k));
    if (scenario) {
      while (next_fault < scenario->faults.size() && scenario->faults[next_fault].t_s <= session->time_s()) {
        runner::apply_fault(scenario->faults[next_fault++], *session);
      }
    }
    driver::RuntimeSettings settings = session->runtime();
    bool changed = k == 0;
    const auto input = console->poll(settings, changed);
    if (changed) session->set_runtime(settings);
    const runner::CycleRecord& cycle = session->step(input ? &*input : nullptr);
    if (recorder) {
      recorder->record(cycle, changed ? std::optional(session->runtime()) : std::nullopt,
                       session->status(), session->rover());
    }
    if (k % static_cast<std::uint64_t>(status_every) == 0) console->publish(session->status(), truth_json(session->rover()));
    if (!args.quiet && k % 64 == 0) print_status_line(session->time_s(), session->status(), out);
    if (args.duration_s > 0.0 && session->time_s() >= args.duration_s) break;
  }
  out << "stopped after " << session->time_s() << " s\n";
  return 0;
}

int run_sim(const SimArgs& args, const Params& params, std::ostream& out, std::ostream& err) {
  std::optional<runner::Scenario> scenario;
  std::unique_ptr<sim::SimulatedRover> rover;
  std::mutex mutex;
  std::vector<protocol::CanFrame> inbox;
  std::unique_ptr<bus::SocketcandServer> server;
  try {
    rover = std::make_unique<sim::SimulatedRover>(params, sim_options(args.scenario, args.seed, scenario));
    const link::ListenAddress listen = link::parse_listen_address(args.listen);
    bus::SocketcandServer::Config config;
    config.address = listen.address;
    config.port = listen.port;
    config.channel = args.channel;
    server = std::make_unique<bus::SocketcandServer>(config, [&](const protocol::CanFrame& f) {
      const std::lock_guard lock(mutex);
      inbox.push_back(f);
    });
    server->start();
  } catch (const std::exception& e) {
    err << "marsokhod sim: " << e.what() << "\n";
    return kUsageError;
  }
  out << "socketcand: listening on " << args.listen.substr(0, args.listen.rfind(':')) << ":"
      << server->port() << ", channel " << args.channel << "\n" << std::flush;
  install_signal_handlers();
  const auto start = Clock::now();
  constexpr auto kStep = std::chrono::milliseconds(1);
  for (std::int64_t k = 1; !g_stop; ++k) {
    std::this_thread::sleep_until(start + kStep * k);
    std::vector<protocol::CanFrame> frames;
    {
      const std::lock_guard lock(mutex);
      frames.swap(inbox);
    }
    for (const auto& f : frames) rover->send(f, rover->time_s());
    for (const sim::TimedFrame& f : rover->advance_to(static_cast<double>(k) * 1e-3)) {
      server->broadcast(f.frame, f.time_s);
    }
    if (args.duration_s > 0.0 && rover->time_s() >= args.duration_s) break;
  }
  server->stop();
  out << "stopped after " << rover->time_s() << " s\n";
  return 0;
}

int run_drive(const DriveArgs& args, const Params& params, std::ostream& out, std::ostream& err) {
  std::unique_ptr<bus::CanTransport> transport;
  std::unique_ptr<ConsoleLink> console;
  try {
    transport = bus::open_transport(args.can);
    console = std::make_unique<ConsoleLink>(params, args.console, out);
  } catch (const std::exception& e) {
    err << "marsokhod drive: " << e.what() << "\n";
    return kUsageError;
  }
  out << "driving over " << transport->name() << "; " << describe_calibration(params) << "\n"
      << std::flush;
  install_signal_handlers();
  driver::Driver driver(params);
  const auto start = Clock::now();
  const auto period = std::chrono::microseconds(std::llround(params.cycle.period_s * 1e6));
  std::vector<protocol::CanFrame> received;
  for (std::uint64_t k = 0; !g_stop; ++k) {
    const auto deadline = start + period * static_cast<std::int64_t>(k);
    try {
      for (auto now = Clock::now(); now < deadline; now = Clock::now()) {
        auto frames = transport->receive(std::chrono::duration_cast<std::chrono::microseconds>(deadline - now));
        received.insert(received.end(), frames.begin(), frames.end());
      }
      driver::RuntimeSettings settings = driver.runtime();
      bool changed = false;
      const auto input = console->poll(settings, changed);
      if (changed) driver.set_runtime(settings);
      const double t = std::chrono::duration<double>(deadline - start).count();
      for (const auto& f : driver.step(t, received, input ? &*input : nullptr)) transport->send(f);
    } catch (const bus::TransportError& e) {
      err << "marsokhod drive: " << e.what() << "\n";
      return 1;
    }
    received.clear();
    console->publish(driver.status(), nullptr);
    if (!args.quiet && k % 64 == 0) print_status_line(driver.status().mission_time_s, driver.status(), out);
    if (args.duration_s > 0.0 && driver.status().mission_time_s >= args.duration_s) break;
  }
  out << "stopped\n";
  return 0;
}

}  // namespace marsokhod::app
