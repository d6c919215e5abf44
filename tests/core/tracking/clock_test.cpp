#include "core/tracking/clock.hpp"

#include <cstdint>
#include <limits>

#include "tracking_test_support.hpp"

namespace marsokhod::tracking {
namespace {

static_assert(counter_difference(11, 0) == 11);
static_assert(counter_difference(5, 65530) == 11);  // across the wrap: 6 ticks to 0, then 5
static_assert(counter_difference(7, 7) == 0);
static_assert(counter_difference(0, 1) == 65535);

TEST(Clock, OverflowPeriodIsConPlusOneTimes32768Milliseconds) {
  // T(con) = (con+1)·65536/2e6: 0.032768 s at con = 0, 0.065536 s at con = 1, 8.388608 s at 255.
  EXPECT_DOUBLE_EQ(clock_overflow_period_s(0), 0.032768);
  EXPECT_DOUBLE_EQ(clock_overflow_period_s(1), 0.065536);
  EXPECT_DOUBLE_EQ(clock_overflow_period_s(255), 8.388608);
  EXPECT_DOUBLE_EQ(clock_tick_s(0), 0.5e-6);
  // The 64 Hz cycle h = 0.0156 s fits below T(0), as (3.2) requires.
  EXPECT_LT(0.0156, clock_overflow_period_s(0));
}

TEST(Clock, ElapsedAcrossOneWrap) {
  // tim 65000 → 500: (500 − 65000) mod 65536 = 1036 ticks; · 0.5 µs = 0.518 ms at con = 0.
  EXPECT_DOUBLE_EQ(clock_elapsed_s(65000, 500, 0), 1036 * 0.5e-6);
  EXPECT_DOUBLE_EQ(clock_elapsed_s(65000, 500, 1), 1036 * 1.0e-6);
}

// 20 readings 30000 ticks apart starting at tim = 65000: tim wraps 10 times (65000 + 600000 =
// 10·65536 + 9640). t = start + 600000·(con+1)/2e6: 0.3 s at con = 0, 0.6 s at con = 1.
class ClockAcrossWraps : public ::testing::TestWithParam<int> {};

TEST_P(ClockAcrossWraps, AccumulatesEveryTick) {
  const int con = GetParam();
  ClockTracker clock(10.0);
  std::uint16_t tim = 65000;
  EXPECT_DOUBLE_EQ(clock.update(tim, con), 10.0);  // the first reading is the time origin
  int wraps = 0;
  for (int k = 1; k <= 20; ++k) {
    const std::uint16_t next = static_cast<std::uint16_t>(tim + 30000);
    wraps += next < tim ? 1 : 0;
    tim = next;
    const double expected_s = 10.0 + k * 30000.0 * (con + 1) / 2.0e6;
    EXPECT_NEAR(clock.update(tim, con), expected_s, 1e-12) << "reading " << k;
  }
  EXPECT_EQ(wraps, 10);
  EXPECT_NEAR(clock.time_s(), 10.0 + (con == 0 ? 0.3 : 0.6), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Con0And1, ClockAcrossWraps, ::testing::Values(0, 1));

TEST(Clock, ConChangeCountsEachIntervalAtItsOwnRate) {
  // 10 steps of 30000 ticks at con = 0 (0.15 s), then 10 at con = 1 (0.3 s): t = 0.45 s.
  ClockTracker clock;
  std::uint16_t tim = 0;
  clock.update(tim, 0);
  for (int k = 0; k < 20; ++k) {
    tim = static_cast<std::uint16_t>(tim + 30000);
    clock.update(tim, k < 10 ? 0 : 1);
  }
  EXPECT_NEAR(clock.time_s(), 0.45, 1e-12);
}

TEST(Clock, NoDriftOverAnHourOfCycles) {
  // 64 Hz for one hour: 230400 readings 31250 ticks (15.625 ms) apart at con = 0 → exactly 3600 s.
  ClockTracker clock;
  std::uint16_t tim = 123;
  clock.update(tim, 0);
  for (int k = 0; k < 230400; ++k) {
    tim = static_cast<std::uint16_t>(tim + 31250);
    clock.update(tim, 0);
  }
  EXPECT_DOUBLE_EQ(clock.time_s(), 3600.0);
}

TEST(Clock, RejectsBadConWithoutChangingState) {
  ClockTracker clock;
  clock.update(100, 0);
  EXPECT_THROW(clock.update(200, 256), std::invalid_argument);
  EXPECT_EQ(clock.last_tim(), 100);
  EXPECT_DOUBLE_EQ(clock.time_s(), 0.0);
  EXPECT_THROW(ClockTracker(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::tracking
