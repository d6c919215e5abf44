// The failsafes of failsafes.hpp: the attitude from gravity against closed forms, the filter's
// tolerance of vibration, and the stall's timing to the cycle.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/estimation/failsafes.hpp"

namespace marsokhod::estimation {
namespace {

constexpr double kG = 9.81;
constexpr double kH = 1.0 / 64.0;  // exact in binary: 192 cycles are 3 s to the bit
constexpr double kDeg = std::numbers::pi / 180.0;

// What the accelerometer reads at rest with the chassis rolled by φ (+ left side up) and pitched
// by θ (+ nose down): gravity (0, 0, −g) in the chassis frame, R_x(φ)ᵀ·R_y(θ)ᵀ·(0, 0, −g).
std::array<double, 3> at_rest(double roll_rad, double pitch_rad) {
  return {kG * std::sin(pitch_rad), -kG * std::cos(pitch_rad) * std::sin(roll_rad),
          -kG * std::cos(pitch_rad) * std::cos(roll_rad)};
}

std::optional<std::string> hold(TipOverMonitor& m, const std::array<double, 3>& a, int cycles) {
  std::optional<std::string> fault;
  for (int k = 0; k < cycles; ++k) fault = m.update(a, kH);
  return fault;
}

TEST(TipOverMonitor, TheAttitudeOfAChassisAtRestIsItsRollAndPitch) {
  TipOverMonitor m;
  EXPECT_FALSE(hold(m, at_rest(0.0, 0.0), 1).has_value());
  EXPECT_EQ(m.attitude().roll_rad, 0.0);
  EXPECT_EQ(m.attitude().pitch_rad, 0.0);
  // 30° with the left side up, 12° nose up: 640 cycles (10 s, 40 τ) leave e^−40 of the start.
  EXPECT_FALSE(hold(m, at_rest(30.0 * kDeg, -12.0 * kDeg), 640).has_value());
  EXPECT_NEAR(m.attitude().roll_rad, 30.0 * kDeg, 1e-9);
  EXPECT_NEAR(m.attitude().pitch_rad, -12.0 * kDeg, 1e-9);
}

TEST(TipOverMonitor, ARollBeyondTheLimitIsAFaultOnceTheMeanIsThere) {
  TipOverMonitor m;  // 40°, τ = 0.25 s
  const auto rolled = at_rest(-45.0 * kDeg, 0.0);  // the right side up
  // One reading moves the mean by h/τ = 1/16 of the way: the roll is far from 40° yet.
  EXPECT_FALSE(m.update(rolled, kH).has_value());
  EXPECT_LT(std::abs(m.attitude().roll_rad), 10.0 * kDeg);
  // After k readings the mean is (1 − f)·(0, 0, −g) + f·rolled with f = 1 − (15/16)^k; its roll
  // is 40° where 0.7071·f/(1 − 0.2929·f) = tan 40°: f = 0.8806, k = 32.9: the 33rd reading,
  // 0.52 s.
  int first = 0;
  for (int k = 2; k <= 64 && first == 0; ++k) {
    if (m.update(rolled, kH).has_value()) first = k;
  }
  EXPECT_EQ(first, 33);
  // Ten seconds on it reads the roll itself, and keeps reporting it.
  const auto fault = hold(m, rolled, 640);
  ASSERT_TRUE(fault.has_value());
  EXPECT_NEAR(m.attitude().roll_rad, -45.0 * kDeg, 1e-9);
  EXPECT_EQ(*fault, "tip-over: roll -45.0° beyond the limit 40.0°");
}

TEST(TipOverMonitor, APitchBeyondTheLimitIsAFault) {
  TipOverMonitor m({.roll_rad = 0.5, .pitch_rad = 0.6, .time_constant_s = 0.25});
  EXPECT_FALSE(hold(m, at_rest(0.0, 0.59), 640).has_value());
  const auto fault = hold(m, at_rest(0.0, 0.61), 640);
  ASSERT_TRUE(fault.has_value());
  EXPECT_EQ(fault->rfind("tip-over: pitch 35.0° beyond the limit 34.4°", 0), 0u) << *fault;
}

TEST(TipOverMonitor, VibrationOnASlopeDoesNotTripIt) {
  // 35° nose up on sand: the blades shake the chassis by ±3 m/s² along z and x, in turn, each
  // reading alone up to 49° off the vertical; the mean stays at 35°.
  TipOverMonitor m;
  const auto slope = at_rest(0.0, -35.0 * kDeg);
  for (int k = 0; k < 1280; ++k) {
    auto a = slope;
    const double shake = (k % 2 == 0 ? 3.0 : -3.0);
    a[k % 4 < 2 ? 2 : 0] += shake;
    ASSERT_FALSE(m.update(a, kH).has_value()) << k;
  }
  EXPECT_NEAR(m.attitude().pitch_rad, -35.0 * kDeg, 1.0 * kDeg);
}

TEST(TipOverMonitor, ReadingsNearZeroDoNotCount) {
  TipOverMonitor m;
  hold(m, at_rest(20.0 * kDeg, 0.0), 640);
  const double before = m.attitude().roll_rad;
  EXPECT_FALSE(hold(m, {0.0, 0.5, 0.5}, 64).has_value());  // 0.71 m/s² < g/10: a broken sensor
  EXPECT_EQ(m.attitude().roll_rad, before);
}

TEST(TipOverMonitor, BadLimitsAndInputsAreRejectedByName) {
  EXPECT_THROW(TipOverMonitor({.roll_rad = 0.0}), std::invalid_argument);
  EXPECT_THROW(TipOverMonitor({.pitch_rad = 2.0}), std::invalid_argument);
  EXPECT_THROW(TipOverMonitor({.time_constant_s = 0.0}), std::invalid_argument);
  TipOverMonitor m;
  try {
    m.update({0.0, std::nan(""), -kG}, kH);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("accel_mps2[1]"), std::string::npos) << e.what();
  }
  EXPECT_THROW(m.update({0.0, 0.0, -kG}, 0.0), std::invalid_argument);
}

// Both centre wheels commanded ν, turning at w; the gyro at ω.
StuckInput wheels(double nu, double w, double omega = 0.0, bool driving = true) {
  StuckInput in;
  in.period_s = kH;
  in.no_load_radps.fill(nu);
  in.velocity_radps.fill(w);
  in.yaw_rate_radps = omega;
  in.driving = driving;
  in.motion_asked = true;
  return in;
}

TEST(StuckMonitor, StalledWheelsAreAFaultAfterTheConfiguredTime) {
  StuckMonitor m({.time_s = 3.0});
  const StuckInput stalled = wheels(0.47, -0.01);  // what a rover against a wall showed
  for (int k = 1; k < 192; ++k) ASSERT_FALSE(m.update(stalled).has_value()) << k;
  EXPECT_DOUBLE_EQ(m.stalled_s(), 191.0 / 64.0);
  const auto fault = m.update(stalled);  // the 192nd cycle: 3 s
  ASSERT_TRUE(fault.has_value());
  EXPECT_EQ(*fault, "stuck: the centre wheels turned at 2 % of their command for 3.0 s");
  EXPECT_FALSE(m.update(stalled).has_value());  // reported once
}

TEST(StuckMonitor, TheFaultsShareIsOverTimeNotCycles) {
  // Half a second at 10 % of the command in 1/64-s cycles, then half a second at 0 % in 1/32-s
  // cycles: over the second the wheels turned at 5 % (over the 48 cycles it would be 7 %).
  StuckMonitor m({.time_s = 1.0});
  for (int k = 0; k < 32; ++k) ASSERT_FALSE(m.update(wheels(0.5, 0.05)).has_value());
  StuckInput slow = wheels(0.5, 0.0);
  slow.period_s = 1.0 / 32.0;
  for (int k = 1; k < 16; ++k) ASSERT_FALSE(m.update(slow).has_value());
  const auto fault = m.update(slow);
  ASSERT_TRUE(fault.has_value());
  EXPECT_EQ(*fault, "stuck: the centre wheels turned at 5 % of their command for 1.0 s");
}

TEST(StuckMonitor, ABreakInTheStallStartsItAgain) {
  StuckMonitor m({.time_s = 3.0});
  for (int k = 0; k < 150; ++k) m.update(wheels(0.47, 0.0));
  m.update(wheels(0.47, 0.2));  // 43 % of the command: it moved
  EXPECT_EQ(m.stalled_s(), 0.0);
  for (int k = 1; k < 192; ++k) ASSERT_FALSE(m.update(wheels(0.47, 0.0)).has_value());
  EXPECT_TRUE(m.update(wheels(0.47, 0.0)).has_value());
}

TEST(StuckMonitor, WheelsThatTurnOrARoverThatTurnsOrRestsAreNotStuck) {
  StuckMonitor m;
  for (int k = 0; k < 640; ++k) {
    ASSERT_FALSE(m.update(wheels(1.2, 1.0)).has_value());          // rolling (or digging in)
    ASSERT_FALSE(m.update(wheels(1.2, 0.0, 0.15)).has_value());    // a spin the gyro sees
    ASSERT_FALSE(m.update(wheels(0.15, 0.0)).has_value());         // ν̄ below ν_min
    ASSERT_FALSE(m.update(wheels(1.2, 0.0, 0.0, false)).has_value());  // not driving
    StuckInput holding = wheels(0.5, 0.0);  // v1 = 0 on a slope: the wheels hold the rover
    holding.motion_asked = false;
    ASSERT_FALSE(m.update(holding).has_value());
  }
  StuckMonitor shipped;  // T = 5 s: 320 cycles
  for (int k = 1; k < 320; ++k) ASSERT_FALSE(shipped.update(wheels(1.2, 0.0)).has_value()) << k;
  EXPECT_TRUE(shipped.update(wheels(1.2, 0.0)).has_value());
  StuckMonitor off({.time_s = 0.0});
  for (int k = 0; k < 640; ++k) ASSERT_FALSE(off.update(wheels(1.2, 0.0)).has_value());
}

TEST(StuckMonitor, BadLimitsAndInputsAreRejectedByName) {
  EXPECT_THROW(StuckMonitor({.time_s = -1.0}), std::invalid_argument);
  EXPECT_THROW(StuckMonitor({.turning_share = 1.0}), std::invalid_argument);
  EXPECT_THROW(StuckMonitor({.min_command_radps = 0.0}), std::invalid_argument);
  StuckMonitor m;
  StuckInput in = wheels(1.0, 0.0);
  in.velocity_radps[1] = INFINITY;
  try {
    m.update(in);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("velocity_radps[1]"), std::string::npos) << e.what();
  }
}

// The front and rear joint commanded ν, turning at w.
JointBlockedInput joints(double nu_front, double w_front, double nu_rear = 0.0,
                         double w_rear = 0.0, bool driving = true) {
  JointBlockedInput in;
  in.period_s = kH;
  in.no_load_radps = {nu_front, nu_rear};
  in.velocity_radps = {w_front, w_rear};
  in.driving = driving;
  return in;
}

TEST(JointBlockedMonitor, AJointStalledUnderItsCommandIsAFaultAfterTheConfiguredTime) {
  JointBlockedMonitor m;  // T = 5 s: 320 cycles
  // What the front joint showed contracting with a rigid front wheel in soft sand: driven at
  // 0.72 rad/s, turning at 0.01.
  const JointBlockedInput stalled = joints(0.72, 0.01);
  for (int k = 1; k < 320; ++k) ASSERT_TRUE(m.update(stalled).empty()) << k;
  EXPECT_DOUBLE_EQ(m.stalled_s()[0], 319.0 / 64.0);
  EXPECT_EQ(m.stalled_s()[1], 0.0);
  const auto faults = m.update(stalled);  // the 320th cycle: 5 s
  ASSERT_EQ(faults.size(), 1u);
  EXPECT_EQ(faults[0], "front joint blocked: it turned at 1 % of its command (0.72 rad/s) for 5.0 s");
  EXPECT_TRUE(m.update(stalled).empty());  // reported once
  // The rear joint on its own, negative commands as positive ones.
  JointBlockedMonitor rear({.time_s = 1.0});
  for (int k = 1; k < 64; ++k) ASSERT_TRUE(rear.update(joints(0.0, 0.0, -0.5, 0.05)).empty());
  const auto rear_faults = rear.update(joints(0.0, 0.0, -0.5, 0.05));
  ASSERT_EQ(rear_faults.size(), 1u);
  EXPECT_EQ(rear_faults[0], "rear joint blocked: it turned at 10 % of its command (0.50 rad/s) for 1.0 s");
  // Both at once: both reported in the same cycle, the front first.
  JointBlockedMonitor both({.time_s = 1.0});
  for (int k = 1; k < 64; ++k) ASSERT_TRUE(both.update(joints(0.4, 0.0, 0.4, 0.0)).empty());
  const auto both_faults = both.update(joints(0.4, 0.0, 0.4, 0.0));
  ASSERT_EQ(both_faults.size(), 2u);
  EXPECT_TRUE(both_faults[0].starts_with("front joint blocked")) << both_faults[0];
  EXPECT_TRUE(both_faults[1].starts_with("rear joint blocked")) << both_faults[1];
}

TEST(JointBlockedMonitor, TheFaultsMeanCommandIsOverTimeNotCycles) {
  // Half a second at 0.4 rad/s in 1/64-s cycles, then half a second at 0.8 in 1/32-s cycles:
  // the mean over the second is 0.6 rad/s (over the 48 cycles it would be 0.53).
  JointBlockedMonitor m({.time_s = 1.0});
  for (int k = 0; k < 32; ++k) ASSERT_TRUE(m.update(joints(0.4, 0.0)).empty());
  JointBlockedInput slow = joints(0.8, 0.0);
  slow.period_s = 1.0 / 32.0;
  for (int k = 1; k < 16; ++k) ASSERT_TRUE(m.update(slow).empty());
  const auto faults = m.update(slow);
  ASSERT_EQ(faults.size(), 1u);
  EXPECT_EQ(faults[0], "front joint blocked: it turned at 0 % of its command (0.60 rad/s) for 1.0 s");
}

TEST(JointBlockedMonitor, ABreakInTheStallStartsItAgain) {
  JointBlockedMonitor m({.time_s = 1.0});
  for (int k = 0; k < 50; ++k) m.update(joints(0.7, 0.0));
  m.update(joints(0.7, 0.2));  // 29 % of the command: it moved
  EXPECT_EQ(m.stalled_s()[0], 0.0);
  for (int k = 1; k < 64; ++k) ASSERT_TRUE(m.update(joints(0.7, 0.0)).empty());
  EXPECT_EQ(m.update(joints(0.7, 0.0)).size(), 1u);
}

TEST(JointBlockedMonitor, JointsThatTurnOrRestOrAreNotDrivenAreNotBlocked) {
  JointBlockedMonitor m;
  for (int k = 0; k < 640; ++k) {
    ASSERT_TRUE(m.update(joints(1.41, 1.2, -1.41, -1.3)).empty());     // bending
    ASSERT_TRUE(m.update(joints(0.15, 0.0, 0.1, 0.0)).empty());        // |ν| below ν_min: holding
    ASSERT_TRUE(m.update(joints(0.7, 0.0, 0.7, 0.0, false)).empty());  // not driving
  }
  JointBlockedMonitor off({.time_s = 0.0});
  for (int k = 0; k < 640; ++k) ASSERT_TRUE(off.update(joints(0.7, 0.0, 0.7, 0.0)).empty());
}

TEST(JointBlockedMonitor, BadLimitsAndInputsAreRejectedByName) {
  EXPECT_THROW(JointBlockedMonitor({.time_s = -1.0}), std::invalid_argument);
  EXPECT_THROW(JointBlockedMonitor({.turning_share = 1.0}), std::invalid_argument);
  EXPECT_THROW(JointBlockedMonitor({.min_command_radps = 0.0}), std::invalid_argument);
  JointBlockedMonitor m;
  JointBlockedInput in = joints(0.7, 0.0);
  in.no_load_radps[1] = NAN;
  try {
    m.update(in);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no_load_radps[1]"), std::string::npos) << e.what();
  }
  JointBlockedInput no_time = joints(0.7, 0.0);
  no_time.period_s = 0.0;
  EXPECT_THROW(m.update(no_time), std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::estimation
