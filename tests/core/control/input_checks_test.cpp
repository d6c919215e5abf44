#include "core/control/input_checks.hpp"

#include <gtest/gtest.h>

#include "control_test_support.hpp"

namespace marsokhod::control {
namespace {

using testing::expect_invalid_argument;
using testing::kInfinity;
using testing::kNaN;

TEST(RequireFinite, AcceptsFiniteNumbersIncludingZeroAndExtremes) {
  EXPECT_NO_THROW(require_finite(0.0, "law", "x"));
  EXPECT_NO_THROW(require_finite(-1.5e308, "law", "x"));
  EXPECT_NO_THROW(require_finite(4.9e-324, "law", "x"));
}

TEST(RequireFinite, RejectsNaNAndInfinitiesNamingLawAndArgument) {
  for (const double bad : {kNaN, kInfinity, -kInfinity}) {
    expect_invalid_argument([&] { require_finite(bad, "velocity_control (4.14)", "velocity"); },
                            {"velocity_control (4.14)", "velocity", "finite", "upstream"});
  }
}

TEST(RequirePositive, AcceptsOnlyFinitePositiveNumbers) {
  EXPECT_NO_THROW(require_positive(1e-300, "law", "x"));
  for (const double bad : {0.0, -0.0, -1.0, kNaN, kInfinity}) {
    expect_invalid_argument([&] { require_positive(bad, "ControlParams", "rate_per_s"); },
                            {"ControlParams", "rate_per_s", "> 0", "configuration"});
  }
}

TEST(RequireBounded, AcceptsTheClosedIntervalAndRejectsOutsideOrNaN) {
  EXPECT_NO_THROW(require_bounded(1.0, 1.0, "law", "c"));
  EXPECT_NO_THROW(require_bounded(-1.0, 1.0, "law", "c"));
  for (const double bad : {1.0000001, -2.0, kNaN, kInfinity}) {
    expect_invalid_argument([&] { require_bounded(bad, 1.0, "simulate", "c"); },
                            {"simulate", "c"});
  }
}

}  // namespace
}  // namespace marsokhod::control
