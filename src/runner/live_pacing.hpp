// Real-time pacing for the live commands (live.hpp): cycle k is due at start + k·period, and
// SIGINT or SIGTERM asks the loop to end after its cycle. The deterministic cycle still takes
// time as a value; only these loops look at a clock.
#pragma once

#include <chrono>
#include <cstdint>

namespace marsokhod::runner {

class Pacer {
 public:
  using Clock = std::chrono::steady_clock;

  // Starts the clock and installs the SIGINT and SIGTERM handlers.
  explicit Pacer(std::chrono::microseconds period);

  Clock::time_point deadline(std::uint64_t k) const {
    return start_ + period_ * static_cast<std::int64_t>(k);
  }
  // k·period in seconds: the time of cycle k.
  double seconds(std::uint64_t k) const {
    return std::chrono::duration<double>(period_ * static_cast<std::int64_t>(k)).count();
  }
  void sleep_until(std::uint64_t k) const;
  // A SIGINT or SIGTERM arrived since the pacer started.
  static bool stop_requested();

 private:
  Clock::time_point start_;
  std::chrono::microseconds period_;
};

}  // namespace marsokhod::runner
