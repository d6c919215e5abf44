#include "runner/live.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <optional>
#include <ostream>
#include <thread>
#include <vector>

#include "bus/socketcand_server.hpp"
#include "bus/transport.hpp"
#include "core/estimation/odometry_frame.hpp"
#include "driver/driver.hpp"
#include "link/listen_address.hpp"
#include "link/status_json.hpp"
#include "runner/joint_memory_file.hpp"
#include "runner/live_pacing.hpp"
#include "runner/recorder.hpp"
#include "runner/scenario.hpp"
#include "runner/scenario_runner.hpp"
#include "runner/session.hpp"

namespace marsokhod::runner {
namespace {

constexpr int kUsageError = 2;

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

sim::SimOptions sim_options(const std::string& scenario, std::uint64_t seed,
                            std::optional<Scenario>& loaded, const std::string& firmware = {}) {
  sim::SimOptions options;
  if (!scenario.empty()) {
    loaded = load_scenario(scenario);
    options = loaded->sim;
  }
  options.seed = seed;
  options.firmware_dir = firmware;
  return options;
}

// What answers the driver on the bus, with the driver: the one difference between run and drive.
class LiveBus {
 public:
  virtual ~LiveBus() = default;
  // Until cycle k is due at `deadline`, taking what the bus delivers meanwhile.
  virtual void wait_until(Pacer::Clock::time_point deadline) = 0;
  virtual const driver::RuntimeSettings& runtime() const = 0;
  virtual void set_runtime(const driver::RuntimeSettings& settings) = 0;
  // The driver's cycle at t with the operator's input; `settings_changed` for a recording.
  virtual void step(double t_s, const driver::OperatorInput* input, bool settings_changed) = 0;
  virtual const driver::DriverStatus& status() const = 0;
  virtual double time_s() const = 0;  // the status line's time and --duration's
  virtual nlohmann::json truth() const { return nullptr; }
  virtual std::optional<TruePose> true_pose() const { return std::nullopt; }
  // The last step's frames: received at their bus time (µs), sent at time_us.
  const std::vector<std::pair<std::int64_t, protocol::CanFrame>>& received() const {
    return received_frames_;
  }
  const std::vector<protocol::CanFrame>& sent() const { return sent_frames_; }
  std::int64_t step_time_us() const { return step_time_us_; }

 protected:
  std::vector<std::pair<std::int64_t, protocol::CanFrame>> received_frames_;
  std::vector<protocol::CanFrame> sent_frames_;
  std::int64_t step_time_us_ = 0;
};

// `run`: the simulated rover and the driver in lockstep (session.hpp), the scenario's faults at
// their times, every cycle recorded when asked.
class SimulatedBus final : public LiveBus {
 public:
  SimulatedBus(Session& session, const std::optional<Scenario>& scenario, Recorder* recorder,
               const Params& rover_params)
      : session_(&session), scenario_(&scenario), recorder_(recorder),
        joints_(sim::rover_joints(rover_params)) {}
  void wait_until(Pacer::Clock::time_point deadline) override {
    std::this_thread::sleep_until(deadline);
  }
  const driver::RuntimeSettings& runtime() const override { return session_->runtime(); }
  void set_runtime(const driver::RuntimeSettings& settings) override {
    session_->set_runtime(settings);
  }
  void step(double /*t_s: the session keeps its own*/, const driver::OperatorInput* input,
            bool settings_changed) override {
    if (scenario_->has_value()) {
      const std::vector<FaultEvent>& faults = (*scenario_)->faults;
      while (next_fault_ < faults.size() && faults[next_fault_].t_s <= session_->time_s()) {
        apply_fault(faults[next_fault_++], *session_);
      }
    }
    const CycleRecord& cycle = session_->step(input);
    follow_truth_odometry(*session_, cycle, truth_odometry_);
    received_frames_.clear();
    for (const sim::TimedFrame& f : cycle.received) {
      received_frames_.emplace_back(std::llround(f.time_s * 1e6), f.frame);
    }
    sent_frames_ = cycle.sent;
    step_time_us_ = cycle.time_us;
    if (recorder_ != nullptr) {
      recorder_->record(cycle, settings_changed ? std::optional(session_->runtime()) : std::nullopt,
                        session_->status(), session_->rover());
    }
  }
  const driver::DriverStatus& status() const override { return session_->status(); }
  double time_s() const override { return session_->time_s(); }
  // On a soft soil the ruts around the rover go with the truth once a second of simulated time
  // (a patch of 4000 heights: the 3-D view's ground, not worth the status rate).
  nlohmann::json truth() const override {
    const bool with_soil = session_->time_s() >= next_soil_s_;
    if (with_soil) next_soil_s_ = session_->time_s() + kSoilEveryS;
    return link::truth_json(session_->rover(),
                            truth_odometry_.started() ? std::optional(truth_odometry_.pose())
                                                      : std::nullopt,
                            with_soil);
  }
  std::optional<TruePose> true_pose() const override {
    return true_pose_of(session_->rover().truth(), joints_);
  }

 private:
  Session* session_;
  const std::optional<Scenario>* scenario_;
  Recorder* recorder_;
  std::size_t next_fault_ = 0;
  estimation::OdometryFrameTracker truth_odometry_;  // the truth in the driver's frame
  static constexpr double kSoilEveryS = 1.0;
  mutable double next_soil_s_ = 0.0;  // when truth() next carries the soil's patch
  std::vector<sim::RoverJoint> joints_;  // the URDF's, for /tf/links
};

// `drive`: the driver on a CAN transport; the frames that arrive until a cycle is due are its.
class TransportBus final : public LiveBus {
 public:
  TransportBus(const Params& params, bus::CanTransport& transport,
               std::optional<driver::JointMemory> kept, JointMemoryFile* memory_file,
               Recorder* recorder)
      : driver_(params, kept), transport_(&transport), memory_file_(memory_file),
        recorder_(recorder), kept_(std::move(kept)) {}
  void wait_until(Pacer::Clock::time_point deadline) override {
    for (auto now = Pacer::Clock::now(); now < deadline; now = Pacer::Clock::now()) {
      const auto frames = transport_->receive(
          std::chrono::duration_cast<std::chrono::microseconds>(deadline - now));
      received_.insert(received_.end(), frames.begin(), frames.end());
    }
  }
  const driver::RuntimeSettings& runtime() const override { return driver_.runtime(); }
  void set_runtime(const driver::RuntimeSettings& settings) override {
    driver_.set_runtime(settings);
  }
  void step(double t_s, const driver::OperatorInput* input, bool settings_changed) override {
    // Whole microseconds, as a recording keeps them: its replay steps at the same times.
    const std::int64_t t_us = std::llround(t_s * 1e6);
    const auto& sent = driver_.step(static_cast<double>(t_us) * 1e-6, received_, input);
    for (const auto& f : sent) transport_->send(f);
    received_frames_.clear();
    for (const auto& f : received_) received_frames_.emplace_back(t_us, f);
    sent_frames_ = sent;
    step_time_us_ = t_us;
    if (recorder_ != nullptr) {
      CycleRecord cycle;
      cycle.time_us = t_us;
      for (const auto& f : received_) cycle.received.push_back({static_cast<double>(t_us) * 1e-6, f});
      cycle.sent = sent;
      cycle.input = input;
      if (first_) cycle.kept_joints = kept_;
      recorder_->record(cycle, settings_changed ? std::optional(driver_.runtime()) : std::nullopt,
                        driver_.status());
    }
    first_ = false;
    received_.clear();
    if (memory_file_ == nullptr) return;
    try {
      memory_file_->keep(driver_.joint_memory(), unix_time_s());
    } catch (const std::runtime_error& e) {
      // The rover drives on; a restart would then not find the newest state. Said once.
      if (!memory_error_) std::fprintf(stderr, "marsokhod drive: %s\n", e.what());
      memory_error_ = true;
    }
  }
  const driver::DriverStatus& status() const override { return driver_.status(); }
  double time_s() const override { return driver_.status().mission_time_s; }

 private:
  static double unix_time_s() {
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
        .count();
  }

  driver::Driver driver_;
  bus::CanTransport* transport_;
  JointMemoryFile* memory_file_;
  Recorder* recorder_;
  std::optional<driver::JointMemory> kept_;
  bool first_ = true;
  bool memory_error_ = false;
  std::vector<protocol::CanFrame> received_;
};

// recording.mcap's summary written: 0, or 1 with the reason on `err`.
int finish_recording(Recorder* recorder, const char* command, std::ostream& err) {
  if (recorder == nullptr) return 0;
  try {
    recorder->finish();
  } catch (const std::exception& e) {
    err << "marsokhod " << command << ": " << e.what() << "\n";
    return 1;
  }
  return 0;
}

struct LoopOptions {
  const char* command;  // "run", "drive": for an error
  double duration_s;
  bool quiet;
};

// One cycle every `period` until SIGINT/SIGTERM or the duration: 0, or 1 when the bus failed.
int run_cycles(LiveBus& bus, LiveConsole& console, std::chrono::microseconds period,
               const LoopOptions& o, std::ostream& out, std::ostream& err) {
  const Pacer pacer(period);
  for (std::uint64_t k = 0; !Pacer::stop_requested(); ++k) {
    try {
      bus.wait_until(pacer.deadline(k));
      const link::CycleCommands commands = console.take(bus.runtime());
      if (commands.settings) bus.set_runtime(*commands.settings);
      const bool changed = k == 0 || commands.settings.has_value();
      bus.step(pacer.seconds(k), commands.input ? &*commands.input : nullptr, changed);
    } catch (const bus::TransportError& e) {
      err << "marsokhod " << o.command << ": " << e.what() << "\n";
      return 1;
    }
    console.frames(bus.status(), bus.received(), bus.sent(), bus.step_time_us());
    if (k % console.status_every() == 0) console.publish(bus.status(), bus.truth(), bus.true_pose());
    if (!o.quiet && k % 64 == 0) print_status_line(bus.time_s(), bus.status(), out);
    if (o.duration_s > 0.0 && bus.time_s() >= o.duration_s) break;
  }
  return 0;
}

}  // namespace

int run_live(const RunArgs& args, const config::LoadedConfig& config, std::ostream& out,
             std::ostream& err) {
  const Params& params = config.params;
  std::optional<Scenario> scenario;
  std::unique_ptr<Session> session;
  std::unique_ptr<LiveConsole> console;
  std::unique_ptr<Recorder> recorder;
  try {
    session = std::make_unique<Session>(config.nominal, params,
                                        sim_options(args.scenario, args.seed, scenario));
    console = std::make_unique<LiveConsole>(config, args.console, out);
    if (!args.record.empty()) {
      recorder = std::make_unique<Recorder>(args.record, config.config_file,
                                            config.calibration_file, &params,
                                            "run --seed " + std::to_string(args.seed));
    }
  } catch (const std::exception& e) {
    err << "marsokhod run: " << e.what() << "\n";
    return kUsageError;
  }
  out << config::describe_calibration(config.calibration) << "\n";
  SimulatedBus bus(*session, scenario, recorder.get(), config.nominal);
  run_cycles(bus, *console, std::chrono::microseconds(session->cycle_us()),
             {"run", args.duration_s, args.quiet}, out, err);
  out << "stopped after " << session->time_s() << " s\n";
  return finish_recording(recorder.get(), "run", err);
}

int run_drive(const DriveArgs& args, const config::LoadedConfig& config, std::ostream& out,
              std::ostream& err) {
  const Params& params = config.params;
  std::unique_ptr<bus::CanTransport> transport;
  std::unique_ptr<LiveConsole> console;
  std::unique_ptr<JointMemoryFile> memory_file;
  std::optional<driver::JointMemory> kept;
  std::unique_ptr<Recorder> recorder;
  std::string kept_note = "none kept (no --joint-memory): Procedure 4.3 takes the joints vertical";
  try {
    if (!args.joint_memory.empty()) {
      memory_file = std::make_unique<JointMemoryFile>(args.joint_memory,
                                                      params.safety.joint_memory_max_age_s);
      kept = memory_file->load(std::chrono::duration<double>(
                                   std::chrono::system_clock::now().time_since_epoch()).count(),
                               kept_note);
    }
    transport = bus::open_transport(args.can);
    console = std::make_unique<LiveConsole>(config, args.console, out);
    if (!args.record.empty()) {
      recorder = std::make_unique<Recorder>(args.record, config.config_file,
                                            config.calibration_file, &params, "drive " + args.can);
    }
  } catch (const std::exception& e) {
    err << "marsokhod drive: " << e.what() << "\n";
    return kUsageError;
  }
  out << "driving over " << transport->name() << "; " << config::describe_calibration(config.calibration)
      << "\njoint state: " << kept_note << "\n" << std::flush;
  TransportBus bus(params, *transport, kept, memory_file.get(), recorder.get());
  const auto period = std::chrono::microseconds(std::llround(params.cycle.period_s * 1e6));
  if (const int status = run_cycles(bus, *console, period, {"drive", args.duration_s, args.quiet},
                                    out, err);
      status != 0) {
    finish_recording(recorder.get(), "drive", err);
    return status;
  }
  out << "stopped\n";
  return finish_recording(recorder.get(), "drive", err);
}

int run_sim(const SimArgs& args, const Params& params, std::ostream& out, std::ostream& err) {
  std::optional<Scenario> scenario;
  std::unique_ptr<sim::SimulatedRover> rover;
  std::mutex mutex;
  std::vector<protocol::CanFrame> inbox;
  std::unique_ptr<bus::SocketcandServer> server;
  try {
    rover = std::make_unique<sim::SimulatedRover>(
        params, sim_options(args.scenario, args.seed, scenario, args.firmware));
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
  const Pacer pacer(std::chrono::milliseconds(1));
  for (std::uint64_t k = 1; !Pacer::stop_requested(); ++k) {
    pacer.sleep_until(k);
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

}  // namespace marsokhod::runner
