#include "core/behaviour/input_checks.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "behaviour_test_support.hpp"

namespace marsokhod::behaviour::detail {
namespace {

using test::invalid_argument_message;
using test::kInf;
using test::kNaN;
using ::testing::HasSubstr;

TEST(BehaviourInputChecks, NamesTheArgumentWithItsIndex) {
  EXPECT_EQ(argument_name("duties", 3), "duties[3]");
}

TEST(BehaviourInputChecks, FiniteValuesPassAndNonFiniteOnesAreNamed) {
  EXPECT_NO_THROW(require_finite(-1e300, "f", "x"));
  EXPECT_THAT(invalid_argument_message([] { require_finite(kNaN, "f", "x"); }),
              HasSubstr("f: x = nan; pass a finite value"));
  EXPECT_THAT(invalid_argument_message([] { require_finite(-kInf, "f", "x"); }),
              HasSubstr("f: x = -inf"));
}

TEST(BehaviourInputChecks, PositiveAndNonNegative) {
  EXPECT_NO_THROW(require_positive(1e-300, "f", "h"));
  EXPECT_THAT(invalid_argument_message([] { require_positive(0.0, "f", "h"); }),
              HasSubstr("f: h = 0; it must be finite and greater than 0"));
  EXPECT_THAT(invalid_argument_message([] { require_positive(kInf, "f", "h"); }),
              HasSubstr("h = inf"));
  EXPECT_NO_THROW(require_non_negative(0.0, "f", "gain"));
  EXPECT_THAT(invalid_argument_message([] { require_non_negative(-0.5, "f", "gain"); }),
              HasSubstr("gain = -0.5; it must be finite and not negative"));
  EXPECT_THAT(invalid_argument_message([] { require_non_negative(kNaN, "f", "gain"); }),
              HasSubstr("gain = nan"));
}

TEST(BehaviourInputChecks, WithinIncludesBothEnds) {
  EXPECT_NO_THROW(require_within(0.0, 0.0, 1.0, "f", "rho"));
  EXPECT_NO_THROW(require_within(1.0, 0.0, 1.0, "f", "rho"));
  EXPECT_THAT(invalid_argument_message([] { require_within(1.25, 0.0, 1.0, "f", "rho"); }),
              HasSubstr("f: rho = 1.25; it must be finite and within [0, 1]"));
  EXPECT_THAT(invalid_argument_message([] { require_within(kNaN, 0.0, 1.0, "f", "rho"); }),
              HasSubstr("rho = nan"));
}

}  // namespace
}  // namespace marsokhod::behaviour::detail
