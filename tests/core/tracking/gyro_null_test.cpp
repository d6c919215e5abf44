#include "core/tracking/gyro_null.hpp"

#include <cmath>
#include <limits>

#include "tracking_test_support.hpp"

namespace marsokhod::tracking {
namespace {

using testing::invalid_argument_message;

TEST(GyroNull, MovesOnlyWhileStill) {
  // y⁰ = 505, λ = 0.99, reading 515 while still: y¹ = 0.99·505 + 0.01·515 = 505.1.
  GyroNullFilter filter(505.0, 0.99);
  EXPECT_NEAR(filter.update(515, true), 505.1, 1e-12);
  // While moving, a real turn (reading 600) must not be learnt: y is held.
  for (int k = 0; k < 100; ++k) {
    EXPECT_NEAR(filter.update(600, false), 505.1, 1e-12);
  }
}

TEST(GyroNull, ConvergesGeometricallyTowardTheStillReading) {
  // y^n = 515 − 10·0.99^n: after 100 still cycles 515 − 10·0.36603 = 511.340.
  GyroNullFilter filter(505.0, 0.99);
  for (int k = 0; k < 100; ++k) {
    filter.update(515, true);
  }
  EXPECT_NEAR(filter.null_counts(), 515.0 - 10.0 * std::pow(0.99, 100), 1e-9);
  EXPECT_NEAR(filter.null_counts(), 511.340, 1e-3);
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
