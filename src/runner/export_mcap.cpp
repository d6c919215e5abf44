#include "runner/export_mcap.hpp"

#include <algorithm>
#include <array>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "runner/mcap_recording.hpp"
#include "runner/recorder.hpp"
#include "runner/replay.hpp"

namespace marsokhod::runner {
namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

// telemetry.csv's true pose, one row a cycle, when the file and its columns are there.
class TruePoses {
 public:
  explicit TruePoses(const std::filesystem::path& file) : in_(file) {
    std::string header;
    if (!in_ || !std::getline(in_, header)) return;
    const auto names = split_csv(header);
    const char* wanted[] = {"true_x_m",      "true_y_m",       "true_z_m",
                            "true_roll_rad", "true_pitch_rad", "true_yaw_rad"};
    for (std::size_t k = 0; k < 6; ++k) {
      const auto it = std::find(names.begin(), names.end(), wanted[k]);
      if (it == names.end()) return;
      columns_[k] = static_cast<std::size_t>(it - names.begin());
    }
    ok_ = true;
  }
  // The next row's pose; none when the file has no truth (or ends).
  std::optional<TruePose> next() {
    std::string line;
    if (!ok_ || !std::getline(in_, line)) return std::nullopt;
    const auto cells = split_csv(line);
    TruePose p;
    for (std::size_t k = 0; k < 6; ++k) {
      if (columns_[k] >= cells.size() || cells[columns_[k]].empty()) return std::nullopt;
      double& v = k < 3 ? p.position_m[k] : p.roll_pitch_yaw_rad[k - 3];
      try {
        v = std::stod(cells[columns_[k]]);
      } catch (const std::exception&) {
        return std::nullopt;
      }
    }
    return p;
  }

 private:
  std::ifstream in_;
  std::array<std::size_t, 6> columns_{};
  bool ok_ = false;
};

}  // namespace

ExportResult export_mcap(const std::filesystem::path& folder, const Params& params,
                         std::unique_ptr<driver::Driver> start, bool overwrite) {
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) {
    throw std::runtime_error("'" + folder.string() + "' is not a folder with a recording");
  }
  for (const char* file : {"can.log", "operator.jsonl"}) {
    if (!std::filesystem::is_regular_file(folder / file, ec)) {
      throw std::runtime_error("'" + folder.string() + "' has no " + file +
                               ": not a recording (scenario --out, run --record, drive --record)");
    }
  }
  const auto target = folder / "recording.mcap";
  if (!overwrite && std::filesystem::exists(target, ec)) {
    throw std::runtime_error(target.string() + " exists (--force writes over it)");
  }
  // Written beside and renamed when complete: a failed export leaves no half file.
  const auto partial = folder / "recording.mcap.partial";
  ExportResult result;
  {
    const auto config = folder / "config.toml";
    const auto calibration = folder / "calibration.toml";
    McapRecording recording(
        partial, params, "export-mcap",
        std::filesystem::is_regular_file(config, ec) ? read_text_file(config) : "",
        std::filesystem::is_regular_file(calibration, ec) ? read_text_file(calibration) : "");
    TruePoses truth(folder / "telemetry.csv");
    try {
      replay_cycles(folder, params, std::move(start), [&](const ReplayedCycle& c) {
        ++result.cycles;
        McapCycle m;
        m.time_us = c.time_us;
        m.received = c.received;
        m.sent = c.recorded;  // the bus as recorded: can.log is the ground truth
        m.input = c.input;
        m.runtime = c.runtime;
        m.status = c.status;
        m.true_pose = truth.next();
        result.true_pose = result.true_pose || m.true_pose.has_value();
        if (c.sent != nullptr && *c.sent != c.recorded && result.identical) {
          result.identical = false;
          result.first_difference = c.where + " (t = " + format_time_us(c.time_us) + ")";
        }
        recording.record(m);
        return true;
      });
      recording.finish();
    } catch (...) {
      std::filesystem::remove(partial, ec);
      throw;
    }
    result.messages = recording.message_count();
  }
  std::filesystem::rename(partial, target, ec);
  if (ec) throw std::runtime_error("cannot write " + target.string() + ": " + ec.message());
  return result;
}

}  // namespace marsokhod::runner
