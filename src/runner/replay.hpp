// `marsokhod replay DIR`: re-runs the driver over a recording (can.log + operator.jsonl, with
// DIR/config.toml) and checks that every request it sends is identical, bit for bit, to the
// recording. Each cycle the driver gets exactly the frames the recording says it received, at the
// recorded time, with the recorded operator input and run-time settings.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/params.hpp"
#include "driver/driver.hpp"

namespace marsokhod::runner {

struct ReplayResult {
  std::uint64_t cycles = 0;
  std::uint64_t frames_compared = 0;
  bool identical = false;
  std::string first_difference;  // empty when identical
};

// Throws std::runtime_error naming the file and line for a recording it cannot read. `start`: the
// driver as it was before the recording's first cycle, for a recording that begins in the middle
// of a driver's life (a soak's window, soak.hpp); without it the first cycle starts a fresh one.
ReplayResult replay(const std::filesystem::path& folder, const Params& params,
                    std::unique_ptr<driver::Driver> start = nullptr);

// One cycle of a recording, re-run.
struct ReplayedCycle {
  std::string where;  // operator.jsonl:LINE
  std::int64_t time_us = 0;
  std::vector<std::pair<std::int64_t, protocol::CanFrame>> received;  // with can.log's times
  std::vector<protocol::CanFrame> recorded;  // the requests can.log holds for this cycle
  // The replayed driver's requests and status; nullptr while the recorded driver was down.
  const std::vector<protocol::CanFrame>* sent = nullptr;
  const driver::DriverStatus* status = nullptr;
  const driver::OperatorInput* input = nullptr;
  std::optional<driver::RuntimeSettings> runtime;  // when the line changed them
};

// The driver re-run over a recording as replay() does, each cycle handed to `on_cycle`, which
// returns false to stop. Throws std::runtime_error as replay() does.
void replay_cycles(const std::filesystem::path& folder, const Params& params,
                   std::unique_ptr<driver::Driver> start,
                   const std::function<bool(const ReplayedCycle&)>& on_cycle);

}  // namespace marsokhod::runner
