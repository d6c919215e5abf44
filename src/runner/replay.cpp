#include "runner/replay.hpp"

#include <nlohmann/json.hpp>

#include <fstream>
#include <memory>
#include <stdexcept>
#include <vector>

#include "bus/candump_log.hpp"
#include "driver/driver.hpp"
#include "link/command_json.hpp"
#include "runner/joint_memory_file.hpp"
#include "runner/recorder.hpp"

namespace marsokhod::runner {
namespace {

std::vector<std::pair<std::int64_t, protocol::CanFrame>> read_can_log(
    const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  std::vector<std::pair<std::int64_t, protocol::CanFrame>> frames;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    auto parsed = bus::parse_candump_line(line);
    if (const auto* e = std::get_if<bus::LogParseError>(&parsed)) {
      throw std::runtime_error(file.string() + ":" + std::to_string(number) + ": " + e->reason);
    }
    if (const auto* f = std::get_if<bus::LoggedFrame>(&parsed)) {
      std::int64_t time_us = 0;
      try {
        time_us = parse_time_us(f->timestamp);
      } catch (const std::invalid_argument& e) {
        throw std::runtime_error(file.string() + ":" + std::to_string(number) + ": " + e.what());
      }
      frames.emplace_back(time_us, f->frame);
    }
  }
  return frames;
}

std::string describe(const protocol::CanFrame& f) {
  bus::LoggedFrame logged;
  logged.timestamp = "0.000000";
  logged.interface = "can0";
  logged.frame = f;
  const std::string line = bus::format_candump_line(logged);
  return line.substr(line.rfind(' ') + 1);
}

}  // namespace

void replay_cycles(const std::filesystem::path& folder, const Params& params,
                   std::unique_ptr<driver::Driver> start,
                   const std::function<bool(const ReplayedCycle&)>& on_cycle) {
  const auto frames = read_can_log(folder / "can.log");
  std::ifstream log(folder / "operator.jsonl");
  if (!log) throw std::runtime_error("cannot read " + (folder / "operator.jsonl").string());
  std::unique_ptr<driver::Driver> driver = std::move(start);
  driver::RuntimeSettings runtime = driver::runtime_settings_from(params);
  std::size_t cursor = 0;
  std::string text;
  int number = 0;
  auto take = [&](std::size_t n, const std::string& where) {
    if (cursor + n > frames.size()) throw std::runtime_error(where + ": can.log ends early");
    std::vector<std::pair<std::int64_t, protocol::CanFrame>> out(
        frames.begin() + static_cast<std::ptrdiff_t>(cursor),
        frames.begin() + static_cast<std::ptrdiff_t>(cursor + n));
    cursor += n;
    return out;
  };
  while (std::getline(log, text)) {
    ReplayedCycle cycle;
    cycle.where = (folder / "operator.jsonl").string() + ":" + std::to_string(++number);
    const std::string& where = cycle.where;
    nlohmann::json line;
    try {
      line = nlohmann::json::parse(text);
      cycle.time_us = parse_time_us(line.at("t").get<std::string>());
      cycle.received = take(line.at("rx").get<std::size_t>(), where);
      for (const auto& f : take(line.at("tx").get<std::size_t>(), where)) {
        cycle.recorded.push_back(f.second);
      }
      if (line.contains("runtime")) {
        runtime = link::runtime_settings_from_json(line["runtime"], runtime);
        cycle.runtime = runtime;
      }
    } catch (const nlohmann::json::exception& e) {
      throw std::runtime_error(where + ": " + e.what());
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(where + ": " + e.what());
    }
    if (!line.at("running").get<bool>()) {
      driver.reset();
      if (!on_cycle(cycle)) return;
      continue;
    }
    if (!driver) {
      std::optional<driver::JointMemory> kept;
      if (line.contains("kept_joints")) kept = joint_memory_from_json(line["kept_joints"], where);
      driver = std::make_unique<driver::Driver>(params, kept);
    }
    driver->set_runtime(runtime);
    std::optional<driver::OperatorInput> input;
    if (!line.at("input").is_null()) input = link::operator_input_from_json(line["input"]);
    std::vector<protocol::CanFrame> received;
    for (const auto& f : cycle.received) received.push_back(f.second);
    cycle.sent = &driver->step(static_cast<double>(cycle.time_us) * 1e-6, received,
                               input ? &*input : nullptr);
    cycle.status = &driver->status();
    cycle.input = input ? &*input : nullptr;
    if (!on_cycle(cycle)) return;
  }
}

ReplayResult replay(const std::filesystem::path& folder, const Params& params,
                    std::unique_ptr<driver::Driver> start) {
  ReplayResult result;
  bool differed = false;
  replay_cycles(folder, params, std::move(start), [&](const ReplayedCycle& c) {
    ++result.cycles;
    if (c.sent == nullptr) return true;
    const auto& sent = *c.sent;
    const auto& recorded = c.recorded;
    for (std::size_t i = 0; i < std::max(sent.size(), recorded.size()); ++i) {
      if (i < sent.size() && i < recorded.size() && sent[i] == recorded[i]) {
        ++result.frames_compared;
        continue;
      }
      result.first_difference =
          c.where + " (t = " + format_time_us(c.time_us) + "): request " + std::to_string(i) +
          " recorded " + (i < recorded.size() ? describe(recorded[i]) : "nothing") +
          ", replayed " + (i < sent.size() ? describe(sent[i]) : "nothing");
      differed = true;
      return false;
    }
    return true;
  });
  result.identical = !differed;
  return result;
}

}  // namespace marsokhod::runner
