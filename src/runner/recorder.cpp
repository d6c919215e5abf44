#include "runner/recorder.hpp"

#include <cctype>
#include <stdexcept>

#include "bus/candump_log.hpp"
#include "link/command_json.hpp"
#include "link/status_json.hpp"
#include "runner/joint_memory_file.hpp"
#include "runner/telemetry.hpp"

namespace marsokhod::runner {
namespace {

std::ofstream open_for_writing(const std::filesystem::path& path) {
  std::ofstream out(path, std::ios::trunc);
  if (!out) throw std::runtime_error("cannot write " + path.string());
  return out;
}

void log_frame(std::ofstream& out, std::int64_t time_us, const protocol::CanFrame& frame) {
  bus::LoggedFrame logged;
  logged.timestamp = format_time_us(time_us);
  logged.interface = "can0";
  logged.frame = frame;
  out << bus::format_candump_line(logged) << '\n';
}

}  // namespace

std::string format_time_us(std::int64_t time_us) {
  char text[40];
  std::snprintf(text, sizeof text, "%lld.%06lld", static_cast<long long>(time_us / 1000000),
                static_cast<long long>(time_us % 1000000));
  return text;
}

std::int64_t parse_time_us(const std::string& text) {
  const auto dot = text.find('.');
  const bool ok = dot != std::string::npos && dot > 0 && text.size() - dot - 1 == 6 &&
                  std::all_of(text.begin(), text.end(),
                              [](char c) { return c == '.' || std::isdigit(static_cast<unsigned char>(c)); });
  if (!ok) throw std::invalid_argument("time '" + text + "' is not SECONDS.MICROSECONDS");
  return std::stoll(text.substr(0, dot)) * 1000000 + std::stoll(text.substr(dot + 1));
}

Recorder::Recorder(const std::filesystem::path& folder, const std::filesystem::path& config_file,
                   const std::filesystem::path& calibration_file, const Params* mcap_params,
                   const std::string& source) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw std::runtime_error("cannot create " + folder.string() + ": " + ec.message());
  can_ = open_for_writing(folder / "can.log");
  operator_ = open_for_writing(folder / "operator.jsonl");
  telemetry_ = open_for_writing(folder / "telemetry.csv");
  telemetry_ << telemetry_header() << '\n';
  if (!config_file.empty()) {
    std::filesystem::copy_file(config_file, folder / "config.toml",
                               std::filesystem::copy_options::overwrite_existing, ec);
    if (ec) throw std::runtime_error("cannot copy " + config_file.string() + ": " + ec.message());
  }
  if (!calibration_file.empty()) {
    std::filesystem::copy_file(calibration_file, folder / "calibration.toml",
                               std::filesystem::copy_options::overwrite_existing, ec);
    if (ec) {
      throw std::runtime_error("cannot copy " + calibration_file.string() + ": " + ec.message());
    }
  }
  if (mcap_params != nullptr) {
    joints_ = sim::rover_joints(*mcap_params);
    mcap_ = std::make_unique<McapRecording>(folder / "recording.mcap", *mcap_params, source,
                                            read_text_file(config_file),
                                            read_text_file(calibration_file));
  }
}

void Recorder::record(const CycleRecord& cycle,
                      const std::optional<driver::RuntimeSettings>& runtime,
                      const driver::DriverStatus& status, const sim::SimulatedRover& rover) {
  record(cycle, runtime, status, &rover);
}

void Recorder::record(const CycleRecord& cycle,
                      const std::optional<driver::RuntimeSettings>& runtime,
                      const driver::DriverStatus& status) {
  record(cycle, runtime, status, nullptr);
}

void Recorder::finish() {
  if (mcap_) mcap_->finish();
}

void Recorder::record(const CycleRecord& cycle,
                      const std::optional<driver::RuntimeSettings>& runtime,
                      const driver::DriverStatus& status, const sim::SimulatedRover* rover) {
  for (const sim::TimedFrame& f : cycle.received) {
    log_frame(can_, std::llround(f.time_s * 1e6), f.frame);
  }
  for (const protocol::CanFrame& f : cycle.sent) log_frame(can_, cycle.time_us, f);
  nlohmann::json line = {{"t", format_time_us(cycle.time_us)},
                         {"rx", cycle.received.size()},
                         {"tx", cycle.sent.size()},
                         {"running", cycle.driver_running},
                         {"input", cycle.input ? link::operator_input_json(*cycle.input) : nlohmann::json()}};
  if (runtime) line["runtime"] = link::runtime_settings_json(*runtime);
  if (cycle.kept_joints) line["kept_joints"] = joint_memory_json(*cycle.kept_joints);
  operator_ << line.dump() << '\n';
  telemetry_ << telemetry_row(static_cast<double>(cycle.time_us) * 1e-6, cycle.driver_running,
                              status, rover)
             << '\n';
  if (!mcap_) return;
  McapCycle m;
  m.time_us = cycle.time_us;
  for (const sim::TimedFrame& f : cycle.received) {
    m.received.emplace_back(std::llround(f.time_s * 1e6), f.frame);
  }
  m.sent = cycle.sent;
  m.input = cycle.input;
  m.runtime = runtime;
  m.status = cycle.driver_running ? &status : nullptr;
  if (rover != nullptr) {
    m.truth = link::truth_json(*rover);
    const sim::GroundTruth t = rover->truth();
    m.true_pose = true_pose_of(t, joints_);
  }
  mcap_->record(m);
}

}  // namespace marsokhod::runner
