// Step 2 of the control cycle: the frames that arrived since the last cycle, decoded and sorted
// by controller. Lost, late, duplicated or malformed frames never stop the cycle: they are counted
// (and the first reason kept) for the status, and a controller that stays silent for
// missed_responses_limit cycles in a row is reported as a fault.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "core/params.hpp"
#include "core/protocol/codec.hpp"

namespace marsokhod::driver {

struct BusCounters {
  std::uint64_t frames = 0;         // every frame seen
  std::uint64_t malformed = 0;      // rejected by the codec
  std::uint64_t duplicates = 0;     // a second response of one controller within a cycle
  std::uint64_t foreign = 0;        // requests on the bus (e.g. µ8's own stop frames)
  std::uint64_t missed = 0;         // cycles × controllers without the expected response
  std::string last_error;           // the codec's reason for the latest malformed frame
};

// What one cycle brought in.
struct CycleResponses {
  std::array<std::optional<protocol::ControlResponse>, kMotorCount> control;
  std::array<std::optional<protocol::ConfigurationResponse>, kMotorCount> configuration;
  std::optional<protocol::MeasurementResponse> measurement;
  bool dead_man_acknowledged = false;
};

class FrameIntake {
 public:
  explicit FrameIntake(int icr);

  // Decodes and sorts the frames of one cycle. `expected_control[i]` says whether µi was sent a
  // control request last cycle (and so owes a response); missing ones count toward its silence.
  CycleResponses take(std::span<const protocol::CanFrame> frames,
                      const std::array<bool, kMotorCount + 1>& expected);

  const BusCounters& counters() const { return counters_; }
  // Consecutive cycles each controller (µ0–µ8) owed a response and gave none.
  const std::array<int, kMotorCount + 1>& silent_cycles() const { return silent_cycles_; }

 private:
  void sort(const protocol::Message& message, CycleResponses& out);

  protocol::DecodeContext context_;
  BusCounters counters_;
  std::array<int, kMotorCount + 1> silent_cycles_{};
};

}  // namespace marsokhod::driver
