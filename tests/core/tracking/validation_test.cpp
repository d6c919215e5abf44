#include "core/tracking/validation.hpp"

#include <limits>

#include "tracking_test_support.hpp"

namespace marsokhod::tracking {
namespace {

using ::testing::HasSubstr;
using testing::invalid_argument_message;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();

TEST(TrackingValidation, FiniteAcceptsNumbersRejectsNaNAndInfinityByName) {
  EXPECT_NO_THROW(detail::require_finite(-3.0, "x"));
  EXPECT_THAT(
      invalid_argument_message([] { detail::require_finite(kNaN, "sensors.gravity_mps2"); }),
      HasSubstr("sensors.gravity_mps2"));
  EXPECT_THAT(invalid_argument_message([] { detail::require_finite(kInfinity, "y"); }),
              HasSubstr("finite"));
}

TEST(TrackingValidation, MessageSaysWhatToDo) {
  EXPECT_THAT(
      invalid_argument_message([] { detail::require_positive(-1.0, "sensors.gravity_mps2"); }),
      HasSubstr("config/marsokhod.toml"));
  EXPECT_THAT(
      invalid_argument_message([] { detail::require_finite(kNaN, "start_time_s", "pass a time"); }),
      HasSubstr("start_time_s = nan: it must be a finite number; pass a time"));
}

TEST(TrackingValidation, RangeIsClosed) {
  EXPECT_NO_THROW(detail::require_in_range(0.0, 0.0, 1.0, "lambda"));
  EXPECT_NO_THROW(detail::require_in_range(1.0, 0.0, 1.0, "lambda"));
  EXPECT_THAT(invalid_argument_message([] { detail::require_in_range(1.01, 0.0, 1.0, "lambda"); }),
              HasSubstr("lambda = 1.01"));
  EXPECT_FALSE(
      invalid_argument_message([] { detail::require_in_range(kNaN, 0.0, 1.0, "l"); }).empty());
}

TEST(TrackingValidation, PositiveAndNonzero) {
  EXPECT_NO_THROW(detail::require_positive(1e-9, "g"));
  EXPECT_FALSE(invalid_argument_message([] { detail::require_positive(0.0, "g"); }).empty());
  EXPECT_NO_THROW(detail::require_nonzero(-2.0, "gain"));
  EXPECT_FALSE(invalid_argument_message([] { detail::require_nonzero(0.0, "gain"); }).empty());
  EXPECT_FALSE(invalid_argument_message([] { detail::require_nonzero(kNaN, "gain"); }).empty());
}

TEST(TrackingValidation, ConIsAnEightBitRegister) {
  EXPECT_NO_THROW(detail::require_con(0));
  EXPECT_NO_THROW(detail::require_con(255));
  EXPECT_THAT(invalid_argument_message([] { detail::require_con(256); }), HasSubstr("con = 256"));
  EXPECT_THAT(invalid_argument_message([] { detail::require_con(-1); }), HasSubstr("0..255"));
}

}  // namespace
}  // namespace marsokhod::tracking
