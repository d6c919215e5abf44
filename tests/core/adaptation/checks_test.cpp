#include "core/adaptation/checks.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "adaptation_test_util.hpp"

namespace marsokhod::adaptation::detail {
namespace {

using test::invalid_argument_message;
using test::kInf;
using test::kNaN;
using ::testing::HasSubstr;

TEST(AdaptationChecks, NumbersPrintInTheirShortestExactForm) {
  EXPECT_EQ(format_number(0.0157), "0.0157");
  EXPECT_EQ(format_number(-1.2121), "-1.2121");
  EXPECT_EQ(format_number(2.0), "2");
  EXPECT_EQ(format_number(kNaN), "nan");
  EXPECT_EQ(format_number(-kInf), "-inf");
}

TEST(AdaptationChecks, ArgumentNamesCarryTheirIndex) {
  EXPECT_EQ(argument_name("duty", 3), "duty[3]");
}

TEST(AdaptationChecks, FiniteRejectsNaNAndInfinityNamingFunctionAndArgument) {
  EXPECT_NO_THROW(require_finite(-1e300, "f", "x"));
  const std::string message = invalid_argument_message([] { require_finite(kNaN, "f", "x"); });
  EXPECT_THAT(message, HasSubstr("f: x = nan"));
  EXPECT_THAT(invalid_argument_message([] { require_finite(kInf, "f", "x"); }),
              HasSubstr("x = inf"));
}

TEST(AdaptationChecks, PositiveAndNonNegativeDrawTheLineAtZero) {
  EXPECT_NO_THROW(require_positive(1e-300, "f", "x"));
  EXPECT_THAT(invalid_argument_message([] { require_positive(0.0, "f", "x"); }),
              HasSubstr("greater than 0"));
  EXPECT_NO_THROW(require_non_negative(0.0, "f", "x"));
  EXPECT_THAT(invalid_argument_message([] { require_non_negative(-0.1, "f", "x"); }),
              HasSubstr("x = -0.1"));
  EXPECT_THROW(require_non_negative(kInf, "f", "x"), std::invalid_argument);
}

TEST(AdaptationChecks, DutyCyclesLieInMinusOneToOne) {
  EXPECT_NO_THROW(require_duty(-1.0, "f", "d"));
  EXPECT_NO_THROW(require_duty(1.0, "f", "d"));
  EXPECT_THAT(invalid_argument_message([] { require_duty(1.01, "f", "d"); }), HasSubstr("[-1, 1]"));
  EXPECT_THROW(require_duty(kNaN, "f", "d"), std::invalid_argument);
}

TEST(AdaptationChecks, OverflowedResultsAreReportedAsSuch) {
  EXPECT_THAT(invalid_argument_message([] { require_finite_result(kInf, "f", "y"); }),
              HasSubstr("overflowed"));
}

}  // namespace
}  // namespace marsokhod::adaptation::detail
