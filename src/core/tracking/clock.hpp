// (3.2) time of transmission reconstructed from the 16-bit clock tim of one controller µ0–µ7.
//
// tim ticks every (con+1)/2 MHz seconds and overflows every T(con) = (con+1)·65536/2 MHz
// (32.768 ms at con = 0, 65.536 ms at con = 1). Between two readings
//   t^k = t^(k−1) + (con+1)/2e6 · ((tim^k − tim^(k−1)) mod 65536)   [s]      (3.2)
// which is right only if less than T(con) passed between the two readings: the driver must keep
// the cycle period h (and any run of missed responses) below T(con). A longer gap loses whole
// multiples of T(con) without notice. Each controller has its own clock, so each motor keeps its
// own ClockTracker. Time is a value here: no system clock is read.
#pragma once

#include <cstdint>

#include "core/tracking/counter.hpp"

namespace marsokhod::tracking {

inline constexpr double kControllerClockHz = 2.0e6;  // tim prescaler base, chapter 3.2

// (con+1)/2 MHz: the duration of one tick of tim [s]. Throws std::invalid_argument if con ∉ 0..255.
double clock_tick_s(int con);

// T(con) = (con+1)·65536/2 MHz: the period after which tim overflows [s].
double clock_overflow_period_s(int con);

// (3.2): seconds between two readings of tim, assuming less than T(con) passed.
double clock_elapsed_s(std::uint16_t previous_tim, std::uint16_t tim, int con);

// Accumulates (3.2) over the readings of one controller. The first reading is the time origin
// (t = start_time_s); later readings add the elapsed time under the con in force since the
// previous one. Ticks are summed as integers per con, so t carries no rounding drift however
// long the run.
class ClockTracker {
 public:
  // Throws std::invalid_argument if start_time_s is not finite.
  explicit ClockTracker(double start_time_s = 0.0);

  // Feeds tim^k read under the con in force since tim^(k−1); returns t^k [s].
  double update(std::uint16_t tim, int con);

  bool started() const { return started_; }
  double time_s() const { return time_s_; }
  std::uint16_t last_tim() const { return last_tim_; }

 private:
  double start_time_s_;
  double time_s_;
  // Adding tick_s every step would accumulate rounding; instead count ticks at the current con
  // and fold them into base_time_s_ whenever con changes.
  double base_time_s_;
  std::uint64_t ticks_since_base_ = 0;
  int base_con_ = 0;
  std::uint16_t last_tim_ = 0;
  bool started_ = false;
};

}  // namespace marsokhod::tracking
