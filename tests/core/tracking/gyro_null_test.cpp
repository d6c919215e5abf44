#include "core/tracking/gyro_null.hpp"

#include <cmath>
#include <limits>

#include "tracking_test_support.hpp"

namespace marsokhod::tracking {
namespace {

using testing::invalid_argument_message;

TEST(GyroNull, MovesOnlyWhileStill) {
  // y⁰ = 505, reading 515 while still: the first still reading is averaged with y⁰, 510.
  GyroNullFilter filter(505.0, 0.99);
  EXPECT_NEAR(filter.update(515, true), 510.0, 1e-12);
  // While moving, a real turn (reading 600) must not be learnt: y is held.
  for (int k = 0; k < 100; ++k) {
    EXPECT_NEAR(filter.update(600, false), 510.0, 1e-12);
  }
}

TEST(GyroNull, StartsAsTheMeanOfTheStillReadingsThenForgetsGeometrically) {
  // The mean of y⁰ and n readings of 515, (505 + 515·n)/(n + 1), until 1/(n + 1) < 1 − λ:
  // after 99 readings 514.9.
  GyroNullFilter filter(505.0, 0.99);
  for (int k = 0; k < 99; ++k) filter.update(515, true);
  EXPECT_NEAR(filter.null_counts(), (505.0 + 515.0 * 99) / 100.0, 1e-9);
  // Then (3.4) as printed: y^(n+1) = 0.99·y^n + 0.01·reading; a drift to 516 is followed with
  // the time constant of λ: 516 − 1.1·0.99^200 after 200 more.
  for (int k = 0; k < 200; ++k) filter.update(516, true);
  EXPECT_NEAR(filter.null_counts(), 516.0 - (516.0 - 514.9) * std::pow(0.99, 200), 1e-9);
}

TEST(GyroNull, LambdaOneNeverMovesLambdaZeroFollows) {
  GyroNullFilter frozen(505.0, 1.0);
  EXPECT_DOUBLE_EQ(frozen.update(520, true), 505.0);
  GyroNullFilter follower(505.0, 0.0);
  EXPECT_DOUBLE_EQ(follower.update(520, true), 520.0);
}

TEST(GyroNull, RejectsInvalidInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(invalid_argument_message([] { GyroNullFilter(505.0, 1.5); }),
              ::testing::HasSubstr("filters.gyro_null_lambda"));
  EXPECT_THAT(invalid_argument_message([&] { GyroNullFilter(nan, 0.99); }),
              ::testing::HasSubstr("sensors.gyro_null_typ_counts"));
  GyroNullFilter filter(505.0, 0.99);
  EXPECT_THROW(filter.update(nan, true), std::invalid_argument);
  EXPECT_DOUBLE_EQ(filter.null_counts(), 505.0);
}

}  // namespace
}  // namespace marsokhod::tracking
