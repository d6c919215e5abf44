// Field Experiment 1.1 on the tether: the bound of a motor's supply current (every load up to its
// stall torque) and the duty bound D_I that keeps the rover's within the supply's limit.
#include "core/behaviour/supply_current.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "behaviour_test_support.hpp"

namespace marsokhod::behaviour {
namespace {

using test::invalid_argument_message;
using test::kNaN;
using ::testing::HasSubstr;

constexpr double kTolerance = 1e-12;

TEST(SupplyCurrent, AMotorDrawsItsStallTorquesCurrentForTheShareOfThePeriodItConducts) {
  const SupplyCurrentParams p;  // I0 0.12 A, I1 0.06 A s/rad, k_t 7.5, c 1.74 N·m/V, U_dz 1 V
  // d = 0.5 at 24 V: x = 11 V, τ_s = 1.74·11 = 19.14 N·m, I = 0.12 + 0.06·1 + 0.5·19.14/7.5.
  EXPECT_NEAR(motor_current_bound_a(0.5, 1.0, 24.0, p), 0.18 + 0.5 * 19.14 / 7.5, kTolerance);
  // Reversed: the same.
  EXPECT_NEAR(motor_current_bound_a(-0.5, -1.0, 24.0, p), 0.18 + 0.5 * 19.14 / 7.5, kTolerance);
  // d = 1: the whole stall current, 1.74·23/7.5 = 5.336 A.
  EXPECT_NEAR(motor_current_bound_a(1.0, 0.0, 24.0, p), 0.12 + 1.74 * 23.0 / 7.5, kTolerance);
  // In the dead zone (0.03·24 = 0.72 V < 1 V) the motor holds at most 5 N·m.
  EXPECT_NEAR(motor_current_bound_a(0.03, 0.0, 24.0, p), 0.12 + 0.03 * 5.0 / 7.5, kTolerance);
  // The bridge off draws nothing, whatever the shaft does.
  EXPECT_EQ(motor_current_bound_a(0.0, 2.0, 24.0, p), 0.0);
}

// A shaft turning against its duty (plugging: a wheel still spinning the old way as a spin
// reverses) adds its back-EMF to the bridge's voltage: its torque along d may pass the stall
// torque by |w|/B⁻, at most the full-duty stall torque 1.74·23 = 40.02 N·m. At d = 0.2 and 24 V:
// τ_s = 1.74·3.8 = 6.612 N·m; turning back at 0.3 rad/s, 6.612 + 0.3/0.015 = 26.612 N·m; at
// 1 rad/s, 6.612 + 66.7, held at 40.02. Along d, or standing, the stall torque alone.
TEST(SupplyCurrent, AShaftTurningAgainstItsDutyMayPassItsStallTorque) {
  const SupplyCurrentParams p;
  const double stall = 1.74 * 3.8;
  EXPECT_NEAR(motor_current_bound_a(0.2, 0.3, 24.0, p), 0.12 + 0.018 + 0.2 * stall / 7.5,
              kTolerance);
  EXPECT_NEAR(motor_current_bound_a(0.2, 0.0, 24.0, p), 0.12 + 0.2 * stall / 7.5, kTolerance);
  EXPECT_NEAR(motor_current_bound_a(0.2, -0.3, 24.0, p),
              0.12 + 0.018 + 0.2 * (stall + 0.3 / 0.015) / 7.5, kTolerance);
  EXPECT_NEAR(motor_current_bound_a(-0.2, 0.3, 24.0, p),
              0.12 + 0.018 + 0.2 * (stall + 0.3 / 0.015) / 7.5, kTolerance);
  EXPECT_NEAR(motor_current_bound_a(0.2, -1.0, 24.0, p), 0.12 + 0.06 + 0.2 * 1.74 * 23.0 / 7.5,
              kTolerance);
}

TEST(SupplyCurrent, RejectsWhatIsNotADutyASpeedOrAVoltage) {
  const SupplyCurrentParams p;
  EXPECT_THAT(invalid_argument_message([&] { motor_current_bound_a(1.5, 0.0, 24.0, p); }),
              HasSubstr("duty"));
  EXPECT_THAT(invalid_argument_message([&] { motor_current_bound_a(0.5, kNaN, 24.0, p); }),
              HasSubstr("shaft_velocity_radps"));
  EXPECT_THAT(invalid_argument_message([&] { motor_current_bound_a(0.5, 0.0, -1.0, p); }),
              HasSubstr("supply_v"));
}

// Six wheels at one duty d, standing, on 24 V, the joints off: 6·(0.12 + d·1.74·(24d − 1)/7.5) +
// 1.05 = 6 A gives 24d² − d = (4.95 − 0.72)·7.5/(6·1.74) = 3.03879…, d = (1 + √(1 + 96·3.03879))/48
// = 0.37727.
TEST(SupplyCurrent, SixWheelsOnTheTetherGetAbout038) {
  const SupplyCurrentParams p;
  const auto current_at = [&](double d) {
    double total_a = p.base_current_a;
    for (int wheel = 0; wheel < 6; ++wheel) total_a += motor_current_bound_a(d, 0.0, 24.0, p);
    return total_a;
  };
  const double c = (4.95 - 0.72) * 7.5 / (6.0 * 1.74);
  const double expected = (1.0 + std::sqrt(1.0 + 96.0 * c)) / 48.0;
  EXPECT_NEAR(expected, 0.37727, 1e-5);
  const double bound = current_duty_bound(0.05, 1.0, p.tether_current_limit_a, current_at);
  // Within the resolution below the closed form, never above it.
  EXPECT_LE(bound, expected);
  EXPECT_GT(bound, expected - kDutyBoundResolution);
  EXPECT_LE(current_at(bound), p.tether_current_limit_a);
}

TEST(SupplyCurrent, TheBoundIsTheWholeRangeOrItsFloorAtTheEnds) {
  const auto linear = [](double d) { return 1.0 + 10.0 * d; };
  EXPECT_EQ(current_duty_bound(0.05, 0.4, 6.0, linear), 0.4);    // 5 A at 0.4: within
  EXPECT_EQ(current_duty_bound(0.05, 1.0, 1.2, linear), 0.05);   // 1.5 A even at the floor
  const double half = current_duty_bound(0.05, 1.0, 6.0, linear);  // 6 A at exactly 0.5
  EXPECT_LE(half, 0.5);
  EXPECT_GT(half, 0.5 - kDutyBoundResolution);
  // Ten halvings of [0.05, 1] reach the resolution: 0.95/2^10 < 1/1024 < 0.95/2^9.
  int calls = 0;
  current_duty_bound(0.05, 1.0, 6.0, [&](double d) { ++calls; return linear(d); });
  EXPECT_EQ(calls, 2 + 10);
}

// The warm start answers exactly what the bisection answers, from any guess, for bounds with
// steps (the pwm counts make the real bound a staircase) and for brackets of any width; and it
// needs two evaluations when the guess is the answer, a few when D_I moved a few cells.
TEST(SupplyCurrent, TheWarmStartAnswersTheBisectionsDoubleFromAnyGuess) {
  const auto staircase = [](double d) { return 1.0 + 10.0 * std::floor(d * 511.0) / 511.0; };
  int compared = 0;
  for (double high : {0.04, 0.3, 0.377, 0.61, 1.0}) {
    const double low = std::min(0.05, high);
    for (double limit : {0.5, 1.7, 3.3, 4.95, 6.0, 11.0, 12.0}) {
      const double cold = current_duty_bound(low, high, limit, staircase);
      for (int k = 0; k < 700; ++k) {  // about every cell of [0.05, 1]'s 1024, and beyond it
        const double guess = -0.1 + 0.00173 * k;
        int calls = 0;
        EXPECT_EQ(current_duty_bound_from(guess, low, high, limit,
                                          [&](double d) {
                                            ++calls;
                                            return staircase(d);
                                          }),
                  cold)
            << "low " << low << " high " << high << " limit " << limit << " guess " << guess;
        // A jump across the bracket: high, the start cell, 5 gallops, the end, 11 halvings of the
        // cells between (the probe takes a cell end beside the middle, not the middle).
        EXPECT_LE(calls, 19);
        ++compared;
      }
      int calls = 0;
      const double warm = current_duty_bound_from(cold, low, high, limit, [&](double d) {
        ++calls;
        return staircase(d);
      });
      EXPECT_EQ(warm, cold);
      if (cold > low && cold < high) {
        EXPECT_EQ(calls, 2) << "high " << high << " limit " << limit;
        // D_I moved by 3 cells either way: at most a gallop of 1, 2 and 4 cells and two halvings.
        for (double moved : {-3.0, 3.0}) {
          calls = 0;
          const double guess = cold - moved * kDutyBoundResolution * 0.95;
          if (guess <= low || guess >= high) continue;
          EXPECT_EQ(current_duty_bound_from(guess, low, high, limit, [&](double d) {
                      ++calls;
                      return staircase(d);
                    }),
                    cold);
          EXPECT_LE(calls, 6) << "high " << high << " limit " << limit << " moved " << moved;
        }
      }
    }
  }
  EXPECT_EQ(compared, 5 * 7 * 700);
}

// Where the bound dips as D grows (the tether scenario's does, by 0.3 A, where two wheels' duties
// pass through 0), the warm start's answer is still admitted by the bound from every guess, and it
// stops on the step it held: from inside the dip it keeps the dip's D, from the step under the dip
// that step (the plain bisection, from [0.05, 1], lands in the dip).
TEST(SupplyCurrent, TheWarmStartOnADippingBoundAnswersAnAdmittedDuty) {
  const auto dipping = [](double d) {
    return 1.0 + 10.0 * d - (d >= 0.52 && d < 0.53 ? 0.3 : 0.0);
  };
  const double limit = 6.05;  // 10d + 1 reaches it at 0.505, and within the dip at 0.535
  for (int k = 0; k < 70; ++k) {
    const double guess = -0.1 + 0.0173 * k;
    const double warm = current_duty_bound_from(guess, 0.05, 1.0, limit, dipping);
    EXPECT_LE(dipping(warm), limit) << "guess " << guess;
    EXPECT_GT(warm, 0.5) << "guess " << guess;
  }
  EXPECT_GT(current_duty_bound_from(0.525, 0.05, 1.0, limit, dipping), 0.52);
  EXPECT_LT(current_duty_bound_from(0.505, 0.05, 1.0, limit, dipping), 0.506);
}

// Where the bound does not bind and the guess lies in the last cell, one evaluation (of `high`).
// A bracket that is not finite goes to the bisection and ends (the gallop alone would run on).
TEST(SupplyCurrent, TheWarmStartAsksHighOnceAndEndsOnABadBracket) {
  const auto linear = [](double d) { return 1.0 + 10.0 * d; };
  int calls = 0;
  EXPECT_EQ(current_duty_bound_from(0.4, 0.05, 0.4, 6.0,
                                    [&](double d) {
                                      ++calls;
                                      return linear(d);
                                    }),
            0.4);
  EXPECT_EQ(calls, 1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // The bisection with a NaN top: NaN is not admitted, the loop's width test fails, `low`.
  EXPECT_EQ(current_duty_bound_from(0.3, 0.05, nan, 6.0, linear), 0.05);
  EXPECT_EQ(current_duty_bound_from(nan, 0.05, 1.0, 6.0, linear),
            current_duty_bound(0.05, 1.0, 6.0, linear));
}

}  // namespace
}  // namespace marsokhod::behaviour
