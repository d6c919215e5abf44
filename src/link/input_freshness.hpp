// Per-console guards on what reaches the driver, pure (time is a value):
//  - InputFreshness: a gamepad or targets message must come after the previous one (its seq
//    higher) and must not be older than the console's others by more than max_age_s. After a
//    network stall, TCP delivers the readings held up in the stall as one burst; without this
//    the rover would replay seconds of old stick positions — and restart motion after the
//    driver's timeout had stopped it.
//  - TokenBucket: a message rate limit (excess is dropped and counted by the server).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "link/operator_message.hpp"

namespace marsokhod::link {

class InputFreshness {
 public:
  explicit InputFreshness(double max_age_s) : max_age_s_(max_age_s) {}

  // nullopt: pass it on; else why it is dropped. `arrival_s` is the server's steady clock.
  //
  // The console's clock and the server's are not synchronised, so age is relative: the offset
  // arrival − sent of the quickest message seen so far is the baseline (network delay at its
  // least), and a message whose offset exceeds it by more than max_age_s waited that long
  // somewhere. The baseline creeps up by kDriftPerSecond so that clocks running at slightly
  // different rates do not make every message "old" after hours.
  std::optional<std::string> check(const InputStamp& stamp, double arrival_s);

  static constexpr double kDriftPerSecond = 1e-3;  // 1000 ppm: far above any quartz's drift

 private:
  double max_age_s_;
  std::optional<std::uint64_t> last_seq_;
  std::optional<double> baseline_s_;  // arrival − sent of the quickest message
  double baseline_at_s_ = 0.0;        // when it was measured
};

// At most `rate_per_s` on average, `burst` at once. Starts full.
class TokenBucket {
 public:
  TokenBucket(double rate_per_s, double burst)
      : rate_per_s_(rate_per_s), burst_(burst), tokens_(burst) {}
  // Takes one token at `now_s` if there is one.
  bool take(double now_s);

 private:
  double rate_per_s_;
  double burst_;
  double tokens_;
  std::optional<double> last_s_;
};

}  // namespace marsokhod::link
