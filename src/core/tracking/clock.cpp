#include "core/tracking/clock.hpp"

#include "core/checks/checks.hpp"

namespace marsokhod::tracking {

double clock_tick_s(int con) {
  checks::setting::require_con(con);
  return static_cast<double>(con + 1) / kControllerClockHz;
}

double clock_overflow_period_s(int con) {
  return clock_tick_s(con) * static_cast<double>(kCounterModulus);
}

double clock_elapsed_s(std::uint16_t previous_tim, std::uint16_t tim, int con) {
  return clock_tick_s(con) * static_cast<double>(counter_difference(tim, previous_tim));
}

ClockTracker::ClockTracker(double start_time_s)
    : start_time_s_(start_time_s), time_s_(start_time_s), base_time_s_(start_time_s) {
  checks::setting::require_finite(start_time_s, "start_time_s", "pass a finite start time [s]");
}

double ClockTracker::update(std::uint16_t tim, int con) {
  const double tick_s = clock_tick_s(con);  // validates con before any state changes
  if (!started_) {
    started_ = true;
    last_tim_ = tim;
    base_con_ = con;
    time_s_ = start_time_s_;
    return time_s_;
  }
  if (con != base_con_) {
    base_time_s_ = time_s_;
    ticks_since_base_ = 0;
    base_con_ = con;
  }
  ticks_since_base_ += counter_difference(tim, last_tim_);
  last_tim_ = tim;
  time_s_ = base_time_s_ + tick_s * static_cast<double>(ticks_since_base_);
  return time_s_;
}

}  // namespace marsokhod::tracking
