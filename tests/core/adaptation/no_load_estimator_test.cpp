#include "core/adaptation/no_load_estimator.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "adaptation_test_util.hpp"

namespace marsokhod::adaptation {
namespace {

using test::invalid_argument_message;
using test::kNaN;
using ::testing::HasSubstr;

constexpr double kTolerance = 1e-12;

MotorVector all(double value) {
  MotorVector vector{};
  vector.fill(value);
  return vector;
}

// The table after Procedure 4.8: h = 0.0157 s, con = 0: δ = 0, 0.2452, 0.3742, 0.2798, 0.1008;
// h = 0.0313 s, con = 1: δ = 0, 0.2449, 0.5592, 0.1960.
TEST(SelectResponse, MatchesConExactlyAndThePeriodWithinOneMillisecond) {
  const Params params;
  const auto& responses = params.responses;
  EXPECT_EQ(&select_response(responses, 0.0157, 0), &responses.at(0));
  EXPECT_EQ(&select_response(responses, 0.0156, 0), &responses.at(0));  // CycleParams' h
  EXPECT_EQ(&select_response(responses, 0.0167, 0), &responses.at(0));  // the edge
  EXPECT_EQ(&select_response(responses, 0.0313, 1), &responses.at(1));
}

TEST(SelectResponse, PicksTheNearestPeriodWhenSeveralFit) {
  const std::vector<ResponseParams> responses{{0.0150, 0, {1.0}}, {0.0157, 0, {0.5, 0.5}}};
  EXPECT_EQ(&select_response(responses, 0.0155, 0), &responses.at(1));
  EXPECT_EQ(&select_response(responses, 0.0152, 0), &responses.at(0));
}

TEST(SelectResponse, ListsTheAvailablePairsWhenNoneFits) {
  const Params params;
  const std::string message =
      invalid_argument_message([&] { select_response(params.responses, 0.0157, 1); });
  EXPECT_THAT(message, HasSubstr("h = 0.0157 s, con = 1"));
  EXPECT_THAT(message, HasSubstr("available (h, con): (0.0157 s, 0), (0.0313 s, 1)"));
  EXPECT_THAT(invalid_argument_message([&] { select_response(params.responses, 0.0168, 0); }),
              HasSubstr("within 0.001 s"));
  EXPECT_THAT(invalid_argument_message([&] { select_response(params.responses, kNaN, 0); }),
              HasSubstr("period_s = nan"));
  EXPECT_THAT(invalid_argument_message([] { select_response({}, 0.0157, 0); }),
              HasSubstr("available (h, con): none"));
}

// Example 4.10: h = 0.0157, con = 0, ŵ³ … ŵ⁶ = 0.5, 0.6, 0.65, 0.7, w⁷ = 0.4. With δ⁰ = 0,
//   ν⁷ = δ¹ŵ⁶ + δ²ŵ⁵ + δ³ŵ⁴ + δ⁴ŵ³ = 0.2452·0.7 + 0.3742·0.65 + 0.2798·0.6 + 0.1008·0.5
//      = 0.17164 + 0.24323 + 0.16788 + 0.0504 = 0.63315   (the thesis: 0.6332)
//   l⁷ = 0.4 − 0.63315 = −0.23315                          (the thesis: −0.2332)
TEST(NoLoadEstimator, Example4_10) {
  NoLoadEstimator estimator(select_response(Params{}.responses, 0.0157, 0));
  for (const double w_hat_radps : {0.5, 0.6, 0.65, 0.7}) {
    estimator.push(all(w_hat_radps));
  }
  const MotorVector nu_radps = estimator.no_load_velocity_radps();
  EXPECT_NEAR(nu_radps[kCenterRight], 0.63315, kTolerance);
  const MotorVector load_radps = load(all(0.4), nu_radps);
  EXPECT_NEAR(load_radps[kCenterRight], -0.23315, kTolerance);
  EXPECT_NEAR(load_radps[kCenterRight], -0.2332, 0.00005 + kTolerance);
  // ŵ⁷, the command of cycle 7 itself, carries δ⁰ = 0.
  EXPECT_EQ(estimator.no_load_velocity_radps(all(5.0)), nu_radps);
}

// From rest, a unit step in ŵ appears in ν as the running sum of δ: 0, 0.2452, 0.6194, 0.8992,
// 1.0000, then stays at Σδ = 1.
TEST(NoLoadEstimator, StepResponseIsTheRunningSumOfDelta) {
  NoLoadEstimator estimator(Params{}.responses.at(0));
  const double expected[] = {0.0, 0.2452, 0.6194, 0.8992, 1.0, 1.0};
  for (const double nu : expected) {
    EXPECT_NEAR(estimator.no_load_velocity_radps()[kFrontLeft], nu, kTolerance);
    estimator.push(all(1.0));
  }
}

// After ŵ = 1, 2, …, 20 the ring buffer holds 17 … 20:
//   ν = 0.2452·20 + 0.3742·19 + 0.2798·18 + 0.1008·17 = 4.904 + 7.1098 + 5.0364 + 1.7136 = 18.7638
TEST(NoLoadEstimator, RingBufferKeepsTheNewestCommands) {
  NoLoadEstimator estimator(Params{}.responses.at(0));
  for (int k = 1; k <= 20; ++k) {
    estimator.push(all(k));
  }
  EXPECT_NEAR(estimator.no_load_velocity_radps()[kRearJoint], 18.7638, 1e-11);
}

// con = 1 after ŵ = 1, 2, 3: ν = 0.2449·3 + 0.5592·2 + 0.1960·1 = 0.7347 + 1.1184 + 0.196 = 2.0491.
// Each motor keeps its own history: motor i gets (i + 1) times those commands.
TEST(NoLoadEstimator, SecondTableAndIndependentMotors) {
  NoLoadEstimator estimator(Params{}.responses.at(1));
  for (int k = 1; k <= 3; ++k) {
    MotorVector w_hat_radps{};
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      w_hat_radps[i] = static_cast<double>(k) * static_cast<double>(i + 1);
    }
    estimator.push(w_hat_radps);
  }
  const MotorVector nu_radps = estimator.no_load_velocity_radps();
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    EXPECT_NEAR(nu_radps[i], 2.0491 * static_cast<double>(i + 1), 1e-12) << kMotorNames[i];
  }
}

// Σδ = 0.2452 + 0.3742 + 0.2798 + 0.1008 = 1: a history of 0.5 rad/s estimates 0.5 rad/s.
TEST(NoLoadEstimator, StartsFromAGivenHistory) {
  const NoLoadEstimator estimator(Params{}.responses.at(0), all(0.5));
  EXPECT_NEAR(estimator.no_load_velocity_radps()[kBackRight], 0.5, kTolerance);
}

// A made-up table with δ⁰ = 0.5, δ¹ = 0.5: ν^k = (ŵ^k + ŵ^(k−1))/2.
TEST(NoLoadEstimator, ACurrentCommandWeightNeedsTheCommand) {
  NoLoadEstimator estimator(ResponseParams{0.0157, 0, {0.5, 0.5}});
  estimator.push(all(1.0));
  EXPECT_NEAR(estimator.no_load_velocity_radps(all(3.0))[kFrontRight], 2.0, kTolerance);
  EXPECT_THROW(estimator.no_load_velocity_radps(), std::logic_error);
}

TEST(NoLoadEstimator, ASingleCoefficientNeedsNoHistory) {
  NoLoadEstimator estimator(ResponseParams{0.0157, 0, {1.0}});
  estimator.push(all(7.0));
  EXPECT_EQ(estimator.no_load_velocity_radps(all(2.0))[kCenterLeft], 2.0);
}

TEST(NoLoadEstimator, RejectsBadTablesAndNonFiniteCommands) {
  EXPECT_THAT(invalid_argument_message([] {
                NoLoadEstimator(ResponseParams{0.0157, 0, {}});
              }),
              HasSubstr("is empty"));
  EXPECT_THAT(invalid_argument_message([] {
                NoLoadEstimator(ResponseParams{0.0157, 0, {0.0, 0.5, kNaN}});
              }),
              HasSubstr("delta[2] = nan"));
  EXPECT_THAT(
      invalid_argument_message([] { NoLoadEstimator(Params{}.responses.at(0), all(kNaN)); }),
      HasSubstr("initial_w_hat_radps[0] = nan"));

  NoLoadEstimator estimator(Params{}.responses.at(0), all(0.5));
  MotorVector w_hat_radps = all(1.0);
  w_hat_radps[kRearJoint] = kNaN;
  EXPECT_THAT(invalid_argument_message([&] { estimator.push(w_hat_radps); }),
              HasSubstr("NoLoadEstimator::push: w_hat_radps[7] = nan"));
  EXPECT_THROW(estimator.no_load_velocity_radps(w_hat_radps), std::invalid_argument);
  EXPECT_NEAR(estimator.no_load_velocity_radps()[kFrontLeft], 0.5, kTolerance);  // unchanged
}

TEST(NoLoadEstimator, OverflowIsReported) {
  NoLoadEstimator estimator(ResponseParams{0.0157, 0, {0.0, 1e300}});
  estimator.push(all(1e300));
  EXPECT_THAT(invalid_argument_message([&] { estimator.no_load_velocity_radps(); }),
              HasSubstr("overflowed"));
}

// Definition 4.9: l = w − ν.
TEST(LoadDefinition4_9, IsMeasuredMinusNoLoadVelocity) {
  EXPECT_EQ(load(0.5, 0.75), -0.25);
  EXPECT_THAT(invalid_argument_message([] { load(kNaN, 0.0); }),
              HasSubstr("load: measured_velocity_radps = nan"));
  MotorVector nu_radps{};
  nu_radps[kCenterLeft] = kNaN;
  EXPECT_THAT(invalid_argument_message([&] { load(MotorVector{}, nu_radps); }),
              HasSubstr("no_load_velocity_radps[2] = nan"));
  EXPECT_THAT(invalid_argument_message([] { load(1e308, -1e308); }), HasSubstr("overflowed"));
}

}  // namespace
}  // namespace marsokhod::adaptation
