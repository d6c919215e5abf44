#include "core/control/control_params.hpp"

#include <gtest/gtest.h>

#include "control_test_support.hpp"

namespace marsokhod::control {
namespace {

using testing::expect_invalid_argument;
using testing::kInfinity;
using testing::kNaN;

TEST(ControlParams, AcceptsFigure410AndTheJointParameters) {
  EXPECT_NO_THROW(validate(testing::figure_4_10_params()));
  EXPECT_NO_THROW(validate(ControlParams{0.4, 1.4135, 0.0156}));
}

TEST(ControlParams, RejectsEachNonPositiveOrNonFiniteFieldByName) {
  for (const double bad : {0.0, -0.1, kNaN, kInfinity}) {
    expect_invalid_argument([&] { validate(ControlParams{bad, 1.0, 0.0156}); },
                            {"ControlParams", "rate_per_s"});
    expect_invalid_argument([&] { validate(ControlParams{0.1, bad, 0.0156}); },
                            {"ControlParams", "max_speed"});
    expect_invalid_argument([&] { validate(ControlParams{0.1, 1.0, bad}); },
                            {"ControlParams", "period_s"});
  }
}

TEST(ControlParams, DefaultConstructedIsInvalidSoItCannotBeUsedByAccident) {
  expect_invalid_argument([] { validate(ControlParams{}); }, {"rate_per_s"});
}

// Figure 4.11: μ = 0.4, C = w/2 with w = 2.827 rad/s, at the 64 Hz cycle.
TEST(JointControlParams, ComesFromTheJointMotorAndCycleParameters) {
  const ControlParams joint = joint_control_params(Params{});
  EXPECT_DOUBLE_EQ(joint.rate_per_s, 0.4);
  EXPECT_DOUBLE_EQ(joint.max_speed, 1.4135);
  EXPECT_DOUBLE_EQ(joint.period_s, 0.0156);
}

TEST(JointControlParams, RejectsABrokenConfiguration) {
  Params params;
  params.joints.control_speed_fraction = 0.0;
  expect_invalid_argument([&] { joint_control_params(params); }, {"max_speed"});
  params = Params{};
  params.cycle.period_s = kNaN;
  expect_invalid_argument([&] { joint_control_params(params); }, {"period_s"});
}

}  // namespace
}  // namespace marsokhod::control
