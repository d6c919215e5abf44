#include "link/input_freshness.hpp"

#include <algorithm>
#include <cmath>

namespace marsokhod::link {

std::optional<std::string> InputFreshness::check(const InputStamp& stamp, double arrival_s) {
  if (last_seq_ && stamp.seq <= *last_seq_) {
    return "seq " + std::to_string(stamp.seq) + " is not after " + std::to_string(*last_seq_) +
           ": out of order or repeated";
  }
  last_seq_ = stamp.seq;
  const double offset_s = arrival_s - stamp.sent_ms * 1e-3;
  if (!baseline_s_) {
    baseline_s_ = offset_s;
    baseline_at_s_ = arrival_s;
    return std::nullopt;
  }
  const double baseline_now_s =
      *baseline_s_ + kDriftPerSecond * std::max(0.0, arrival_s - baseline_at_s_);
  if (offset_s <= baseline_now_s) {
    baseline_s_ = offset_s;
    baseline_at_s_ = arrival_s;
    return std::nullopt;
  }
  const double late_s = offset_s - baseline_now_s;
  if (late_s > max_age_s_) {
    return "seq " + std::to_string(stamp.seq) + " arrived " +
           std::to_string(static_cast<long long>(std::lround(late_s * 1e3))) +
           " ms later than the console's quickest messages (allowed " +
           std::to_string(static_cast<long long>(std::lround(max_age_s_ * 1e3))) + " ms): stale";
  }
  return std::nullopt;
}

bool TokenBucket::take(double now_s) {
  if (last_s_) tokens_ = std::min(burst_, tokens_ + rate_per_s_ * std::max(0.0, now_s - *last_s_));
  last_s_ = now_s;
  if (tokens_ < 1.0) return false;
  tokens_ -= 1.0;
  return true;
}

}  // namespace marsokhod::link
