#include "core/checks/checks.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "../../support/invalid_argument.hpp"

namespace marsokhod::checks {
namespace {

using ::testing::HasSubstr;
using test_support::expect_invalid_argument;
using test_support::invalid_argument_message;
using test_support::kInf;
using test_support::kNaN;

// "<function>: <argument> = <value>; <requirement>" (adaptation, behaviour).

TEST(Checks, NumbersPrintInTheirShortestExactForm) {
  EXPECT_EQ(format_number(0.0157), "0.0157");
  EXPECT_EQ(format_number(-1.2121), "-1.2121");
  EXPECT_EQ(format_number(2.0), "2");
  EXPECT_EQ(format_number(kNaN), "nan");
  EXPECT_EQ(format_number(-kInf), "-inf");
}

TEST(Checks, ArgumentNamesCarryTheirIndex) {
  EXPECT_EQ(argument_name("duty", 3), "duty[3]");
  EXPECT_EQ(argument_name("duties", 3), "duties[3]");
}

TEST(Checks, FiniteRejectsNaNAndInfinityNamingFunctionAndArgument) {
  EXPECT_NO_THROW(require_finite(-1e300, "f", "x"));
  const std::string message = invalid_argument_message([] { require_finite(kNaN, "f", "x"); });
  EXPECT_THAT(message, HasSubstr("f: x = nan"));
  EXPECT_THAT(invalid_argument_message([] { require_finite(kInf, "f", "x"); }),
              HasSubstr("x = inf"));
}

TEST(Checks, FiniteEstimatesAreNamedAndBlamedUpstream) {
  EXPECT_NO_THROW(require_finite_estimate(-1e300, "f", "x"));
  EXPECT_THAT(invalid_argument_message([] { require_finite_estimate(kNaN, "f", "x"); }),
              HasSubstr("f: x = nan; pass a finite value"));
  EXPECT_THAT(invalid_argument_message([] { require_finite_estimate(kNaN, "f", "x"); }),
              HasSubstr("broken upstream"));
  EXPECT_THAT(invalid_argument_message([] { require_finite_estimate(-kInf, "f", "x"); }),
              HasSubstr("f: x = -inf"));
}

TEST(Checks, PositiveAndNonNegativeDrawTheLineAtZero) {
  EXPECT_NO_THROW(require_positive(1e-300, "f", "x"));
  EXPECT_THAT(invalid_argument_message([] { require_positive(0.0, "f", "x"); }),
              HasSubstr("greater than 0"));
  EXPECT_THAT(invalid_argument_message([] { require_positive(0.0, "f", "h"); }),
              HasSubstr("f: h = 0; it must be finite and greater than 0"));
  EXPECT_THAT(invalid_argument_message([] { require_positive(kInf, "f", "h"); }),
              HasSubstr("h = inf"));
  EXPECT_NO_THROW(require_non_negative(0.0, "f", "x"));
  EXPECT_THAT(invalid_argument_message([] { require_non_negative(-0.1, "f", "x"); }),
              HasSubstr("x = -0.1"));
  EXPECT_THAT(invalid_argument_message([] { require_non_negative(-0.5, "f", "gain"); }),
              HasSubstr("gain = -0.5; it must be finite and not negative"));
  EXPECT_THAT(invalid_argument_message([] { require_non_negative(kNaN, "f", "gain"); }),
              HasSubstr("gain = nan"));
  EXPECT_THROW(require_non_negative(kInf, "f", "x"), std::invalid_argument);
}

TEST(Checks, WithinIncludesBothEnds) {
  EXPECT_NO_THROW(require_within(0.0, 0.0, 1.0, "f", "rho"));
  EXPECT_NO_THROW(require_within(1.0, 0.0, 1.0, "f", "rho"));
  EXPECT_THAT(invalid_argument_message([] { require_within(1.25, 0.0, 1.0, "f", "rho"); }),
              HasSubstr("f: rho = 1.25; it must be finite and within [0, 1]"));
  EXPECT_THAT(invalid_argument_message([] { require_within(kNaN, 0.0, 1.0, "f", "rho"); }),
              HasSubstr("rho = nan"));
}

TEST(Checks, DutyCyclesLieInMinusOneToOne) {
  EXPECT_NO_THROW(require_duty(-1.0, "f", "d"));
  EXPECT_NO_THROW(require_duty(1.0, "f", "d"));
  EXPECT_THAT(invalid_argument_message([] { require_duty(1.01, "f", "d"); }), HasSubstr("[-1, 1]"));
  EXPECT_THROW(require_duty(kNaN, "f", "d"), std::invalid_argument);
}

TEST(Checks, OverflowedResultsAreReportedAsSuch) {
  EXPECT_THAT(invalid_argument_message([] { require_finite_result(kInf, "f", "y"); }),
              HasSubstr("overflowed"));
}

// "<law>: <argument> must be <requirement>, got <value>; <hint>" (control, mobility).

TEST(LawChecks, FiniteAcceptsFiniteNumbersIncludingZeroAndExtremes) {
  EXPECT_NO_THROW(law::require_finite(0.0, "law", "x"));
  EXPECT_NO_THROW(law::require_finite(-1.5e308, "law", "x"));
  EXPECT_NO_THROW(law::require_finite(4.9e-324, "law", "x"));
}

TEST(LawChecks, FiniteRejectsNaNAndInfinitiesNamingLawAndArgument) {
  for (const double bad : {kNaN, kInf, -kInf}) {
    expect_invalid_argument(
        [&] { law::require_finite(bad, "velocity_control (4.14)", "velocity"); },
        {"velocity_control (4.14)", "velocity", "finite", "upstream"});
  }
}

TEST(LawChecks, PositiveAcceptsOnlyFinitePositiveNumbers) {
  EXPECT_NO_THROW(law::require_positive(1e-300, "law", "x"));
  for (const double bad : {0.0, -0.0, -1.0, kNaN, kInf}) {
    expect_invalid_argument([&] { law::require_positive(bad, "ControlParams", "rate_per_s"); },
                            {"ControlParams", "rate_per_s", "> 0", "configuration"});
  }
}

TEST(LawChecks, BoundedAcceptsTheClosedIntervalAndRejectsOutsideOrNaN) {
  EXPECT_NO_THROW(law::require_bounded(1.0, 1.0, "law", "c"));
  EXPECT_NO_THROW(law::require_bounded(-1.0, 1.0, "law", "c"));
  for (const double bad : {1.0000001, -2.0, kNaN, kInf}) {
    expect_invalid_argument([&] { law::require_bounded(bad, 1.0, "simulate", "c"); },
                            {"simulate", "c"});
  }
}

// "invalid <name> = <value>: it must be <requirement>; <remedy>" (tracking).

TEST(SettingChecks, FiniteAcceptsNumbersRejectsNaNAndInfinityByName) {
  EXPECT_NO_THROW(setting::require_finite(-3.0, "x"));
  EXPECT_THAT(
      invalid_argument_message([] { setting::require_finite(kNaN, "sensors.gravity_mps2"); }),
      HasSubstr("sensors.gravity_mps2"));
  EXPECT_THAT(invalid_argument_message([] { setting::require_finite(kInf, "y"); }),
              HasSubstr("finite"));
}

TEST(SettingChecks, MessageSaysWhatToDo) {
  EXPECT_THAT(
      invalid_argument_message([] { setting::require_positive(-1.0, "sensors.gravity_mps2"); }),
      HasSubstr("config/marsokhod.toml"));
  EXPECT_THAT(
      invalid_argument_message([] { setting::require_finite(kNaN, "start_time_s", "pass a time"); }),
      HasSubstr("start_time_s = nan: it must be a finite number; pass a time"));
}

TEST(SettingChecks, RangeIsClosed) {
  EXPECT_NO_THROW(setting::require_in_range(0.0, 0.0, 1.0, "lambda"));
  EXPECT_NO_THROW(setting::require_in_range(1.0, 0.0, 1.0, "lambda"));
  EXPECT_THAT(
      invalid_argument_message([] { setting::require_in_range(1.01, 0.0, 1.0, "lambda"); }),
      HasSubstr("lambda = 1.01"));
  EXPECT_THROW(setting::require_in_range(kNaN, 0.0, 1.0, "l"), std::invalid_argument);
}

TEST(SettingChecks, PositiveAndNonzero) {
  EXPECT_NO_THROW(setting::require_positive(1e-9, "g"));
  EXPECT_THROW(setting::require_positive(0.0, "g"), std::invalid_argument);
  EXPECT_NO_THROW(setting::require_nonzero(-2.0, "gain"));
  EXPECT_THROW(setting::require_nonzero(0.0, "gain"), std::invalid_argument);
  EXPECT_THROW(setting::require_nonzero(kNaN, "gain"), std::invalid_argument);
}

TEST(SettingChecks, ConIsAnEightBitRegister) {
  EXPECT_NO_THROW(setting::require_con(0));
  EXPECT_NO_THROW(setting::require_con(255));
  EXPECT_THAT(invalid_argument_message([] { setting::require_con(256); }), HasSubstr("con = 256"));
  EXPECT_THAT(invalid_argument_message([] { setting::require_con(-1); }), HasSubstr("0..255"));
}

}  // namespace
}  // namespace marsokhod::checks
