#include "sim/firmware/motor_controller.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <variant>

#include "core/protocol/codec.hpp"
#include "core/tracking/motor_position.hpp"
#include "core/tracking/motor_velocity.hpp"
#include "sim/electrics/motor_model.hpp"
#include "sim/electrics/seeded_random.hpp"

namespace marsokhod::sim {
namespace {

using protocol::CanFrame;

constexpr int kPulsesPerRev = 115000;
constexpr double kRadPerPulse = 2.0 * std::numbers::pi / kPulsesPerRev;
constexpr SimTimeNs kMs = 1'000'000;

// The angle half-way into pulse n, so that rounding never decides a count.
double pulse_angle(double pulses) { return (pulses + 0.5) * kRadPerPulse; }

protocol::ControlResponse control(MotorController& controller, bool drv, bool eim,
                                  std::uint16_t pwm) {
  const auto frame = controller.receive(
      protocol::encode(protocol::ControlRequest{controller.node(), drv, eim, pwm}));
  EXPECT_TRUE(frame.has_value());
  const protocol::DecodeResult decoded = protocol::decode(*frame);
  EXPECT_TRUE(decoded.ok());
  return std::get<protocol::ControlResponse>(decoded.message());
}

TEST(SimMotorController, EncoderCountsBothDirectionsAndStpMarksTheReversal) {
  MotorController controller(0, pulse_angle(0), kPulsesPerRev, 1);
  control(controller, false, true, 0);  // eim = 1
  controller.advance(1 * kMs, pulse_angle(100));
  controller.advance(2 * kMs, pulse_angle(70));  // 30 pulses back
  const MotorControllerRegisters registers = controller.registers();
  EXPECT_EQ(registers.enc, 130);
  EXPECT_EQ(registers.stp, 100);
  EXPECT_TRUE(registers.dir);
  controller.advance(3 * kMs, pulse_angle(80));  // forward again: stp = 130
  EXPECT_EQ(controller.registers().enc, 140);
  EXPECT_EQ(controller.registers().stp, 130);
  EXPECT_FALSE(controller.registers().dir);
}

TEST(SimMotorController, MaskedInterruptKeepsDirAndStp) {
  MotorController controller(0, pulse_angle(0), kPulsesPerRev, 1);  // reset: eim = 0
  controller.advance(1 * kMs, pulse_angle(100));
  controller.advance(2 * kMs, pulse_angle(70));
  EXPECT_EQ(controller.registers().enc, 130);
  EXPECT_EQ(controller.registers().stp, 0);
  EXPECT_FALSE(controller.registers().dir);
  // Unmasking does not resynchronise: the next measured change is a change of the line.
  control(controller, false, true, 0);
  controller.advance(3 * kMs, pulse_angle(60));
  EXPECT_FALSE(controller.registers().dir);
  controller.advance(4 * kMs, pulse_angle(65));
  EXPECT_EQ(controller.registers().stp, 140);
  EXPECT_FALSE(controller.registers().dir);  // the line went back to positive
}

TEST(SimMotorController, EncoderWrapsAt65536) {
  MotorController controller(3, pulse_angle(0), kPulsesPerRev, 1);
  controller.advance(1 * kMs, pulse_angle(70000));
  EXPECT_EQ(controller.registers().enc, 70000 - 65536);
  controller.advance(2 * kMs, pulse_angle(-70000));  // 140000 more pulses, backwards
  EXPECT_EQ(controller.registers().enc, (210000 % 65536));
}

TEST(SimMotorController, TimTicksAt2MHzOverConPlusOne) {
  MotorController controller(0, 0.0, kPulsesPerRev, 1);
  controller.advance(1 * kMs, 0.0);
  EXPECT_EQ(controller.registers().tim, 2000);
  controller.advance(40 * kMs, 0.0);
  EXPECT_EQ(controller.registers().tim, 80000 - 65536);
  // con = 1 from 40 ms on: 1 µs per tick.
  const auto response =
      controller.receive(protocol::encode(protocol::ConfigurationRequest{0, 511, 0, 1}));
  ASSERT_TRUE(response.has_value());
  EXPECT_EQ(std::get<protocol::ConfigurationResponse>(protocol::decode(*response).message()).tim,
            14464);
  controller.advance(50 * kMs, 0.0);
  EXPECT_EQ(controller.registers().tim, 14464 + 10000);
}

// 50 pulses per ms from pulse 0.5: the index at t is ⌊0.5 + 50·t/ms⌋.
void turn_steadily(MotorController& controller, int from_ms, int to_ms) {
  for (int ms = from_ms + 1; ms <= to_ms; ++ms) {
    controller.advance(ms * kMs, pulse_angle(50.0 * ms));
  }
}

TEST(SimMotorController, VelCountsTheLastCompletePeriod) {
  MotorController controller(0, pulse_angle(0), kPulsesPerRev, 1, 1);
  turn_steadily(controller, 0, 32);
  EXPECT_EQ(controller.registers().vel, 0);  // no overflow yet (T(0) = 32.768 ms)
  turn_steadily(controller, 32, 40);
  // Pulses up to the overflow at 32.768 ms: ⌊0.5 + 1638.4⌋ = 1638.
  EXPECT_EQ(controller.registers().vel, 1638);
  turn_steadily(controller, 40, 66);
  // Up to 65.536 ms: ⌊0.5 + 3276.8⌋ − 1638 = 3277 − 1638.
  EXPECT_EQ(controller.registers().vel, 1639);
  // (3.3): 1639·25π/47104 = 2.733 rad/s for the true 50 000·2π/115 000 = 2.732 rad/s.
  EXPECT_NEAR(tracking::motor_velocity_radps(1639, false, 0, kPulsesPerRev), 2.7318, 0.002);
}

TEST(SimMotorController, VelWindowMovesInSixteenSlices) {
  MotorController controller(0, pulse_angle(0), kPulsesPerRev, 1, 16);
  turn_steadily(controller, 0, 3);
  // The first slice ends at 4096 ticks = 2.048 ms: ⌊0.5 + 102.4⌋ = 102.
  EXPECT_EQ(controller.registers().vel, 102);
  turn_steadily(controller, 3, 34);
  EXPECT_EQ(controller.registers().vel, 1638);  // 16 slices = one full T(0)
  turn_steadily(controller, 34, 35);
  // Slices 2..17, 2.048 → 34.816 ms: ⌊0.5 + 1740.8⌋ − 102 = 1741 − 102.
  EXPECT_EQ(controller.registers().vel, 1639);
}

TEST(SimMotorController, AnswersControlRequestsWithItsRegisters) {
  MotorController controller(5, pulse_angle(0), kPulsesPerRev, 1, 1);
  turn_steadily(controller, 0, 40);
  const protocol::ControlResponse response = control(controller, true, true, 255);
  EXPECT_EQ(response.node, 5);
  EXPECT_EQ(response.tim, 80000 - 65536);
  EXPECT_EQ(response.enc, 2000);
  EXPECT_EQ(response.stp, 0);
  EXPECT_FALSE(response.dir);
  EXPECT_EQ(response.vel, 1638);
  EXPECT_DOUBLE_EQ(controller.duty(), -255.0 / 511.0);
}

TEST(SimMotorController, IgnoresWhatTheFirmwareCannotUse) {
  MotorController controller(2, 0.0, kPulsesPerRev, 1);
  control(controller, false, true, 100);
  // pwm above the configured icr (|d| > 1): no answer, pwm unchanged.
  EXPECT_FALSE(controller.receive(protocol::encode(protocol::ControlRequest{2, false, true, 600})));
  EXPECT_EQ(controller.registers().pwm, 100);
  // Wrong DLC, another node's request, a response, reserved bits.
  CanFrame frame = protocol::encode(protocol::ControlRequest{2, false, true, 50});
  frame.dlc = 2;
  EXPECT_FALSE(controller.receive(frame));
  EXPECT_FALSE(controller.receive(protocol::encode(protocol::ControlRequest{3, false, true, 50})));
  EXPECT_FALSE(
      controller.receive(protocol::encode(protocol::ControlResponse{2, 0, 0, 0, false, 0})));
  frame = protocol::encode(protocol::ControlRequest{2, false, true, 50});
  frame.data[0] |= 0x80;
  EXPECT_FALSE(controller.receive(frame));
  EXPECT_EQ(controller.registers().pwm, 100);
  // After 0xi2 sets icr = 1023, pwm = 600 is legal.
  ASSERT_TRUE(controller.receive(protocol::encode(protocol::ConfigurationRequest{2, 1023, 0, 0})));
  EXPECT_EQ(controller.registers().pwm, 0);
  control(controller, false, false, 600);
  EXPECT_DOUBLE_EQ(controller.duty(), 600.0 / 1023.0);
}

TEST(SimMotorController, PositionTrackerRecoversTheTrueAngle) {
  // A swing of ±5 rad (±91 500 pulses: enc wraps) with a reversal every 6 s, read every
  // 15.6 ms like the driver's cycle; the shaft moves in 1 ms physics steps.
  const auto angle_at = [](SimTimeNs time_ns) {
    return 0.3 + 5.0 * std::sin(2.0 * std::numbers::pi * ns_to_seconds(time_ns) / 12.0);
  };
  MotorController controller(1, angle_at(0), kPulsesPerRev, 1);
  control(controller, false, true, 0);
  tracking::PositionTracker tracker(angle_at(0), kPulsesPerRev);
  tracker.update(
      {controller.registers().enc, controller.registers().stp, controller.registers().dir});
  double worst_error_rad = 0.0;
  SimTimeNs next_request_ns = 15'600'000;
  for (SimTimeNs time_ns = kMs; time_ns <= 30'000 * kMs; time_ns += kMs) {
    controller.advance(time_ns, angle_at(time_ns));
    if (time_ns >= next_request_ns) {
      next_request_ns += 15'600'000;
      const protocol::ControlResponse response = control(controller, false, true, 0);
      const double position_rad = tracker.update({response.enc, response.stp, response.dir});
      worst_error_rad = std::max(worst_error_rad, std::abs(position_rad - angle_at(time_ns)));
    }
  }
  EXPECT_LT(worst_error_rad, 2.0 * kRadPerPulse);
  EXPECT_EQ(tracker.unknown_reversal_count(), 0U);
}

// Least squares for x in A·x = b with the 5 × 5 normal equations, by Gauss–Jordan elimination.
std::array<double, 5> solve(std::array<std::array<double, 5>, 5> a, std::array<double, 5> b) {
  for (std::size_t i = 0; i < 5; ++i) {
    for (std::size_t row = 0; row < 5; ++row) {
      if (row == i) {
        continue;
      }
      const double factor = a[row][i] / a[i][i];
      for (std::size_t column = 0; column < 5; ++column) {
        a[row][column] -= factor * a[i][column];
      }
      b[row] -= factor * b[i];
    }
  }
  for (std::size_t i = 0; i < 5; ++i) {
    b[i] /= a[i][i];
  }
  return b;
}

TEST(SimMotorController, ProcedureFourEightFindsTheThesisDeltaTable) {
  // Procedure 4.8 on the simulated chain: a random no-load command ŵ^k every h = 15.7 ms (con = 0),
  // the motor's 12 ms lag, the shaft free (w = ω0), and w^k from vel by (3.3); then the least
  // squares w^k = Σ δ^j ŵ^(k−j), j = 0..4.
  const MotorTruth motor;
  MotorModel model(motor);
  MotorController controller(0, pulse_angle(0), kPulsesPerRev, 1);
  SeededRandom random(48);
  std::vector<double> commanded_radps;
  std::vector<double> measured_radps;
  double angle_rad = pulse_angle(0);
  double duty = 0.0;
  constexpr SimTimeNs kPeriodNs = 15'700'000;
  for (SimTimeNs time_ns = 0; time_ns < 120'000 * kMs; time_ns += kMs) {
    if (time_ns % kPeriodNs < kMs) {  // the cycle's request arrives in this millisecond
      if (random.uniform() < 0.25) {
        duty = std::round(random.uniform(0.2, 0.7) * 511.0) / 511.0;
      }
      const protocol::ControlResponse response =
          control(controller, false, true, static_cast<std::uint16_t>(std::lround(duty * 511.0)));
      measured_radps.push_back(
          tracking::motor_velocity_radps(response.vel, false, 0, kPulsesPerRev));
      commanded_radps.push_back(steady_no_load_speed_radps(motor, duty, 24.0, 511));
    }
    angle_rad +=
        model.step(duty, 24.0, 511, model.no_load_speed_radps(), 0.001).no_load_speed_radps * 0.001;
    controller.advance(time_ns + kMs, angle_rad);
  }
  std::array<std::array<double, 5>, 5> normal{};
  std::array<double, 5> right{};
  for (std::size_t k = 4; k < measured_radps.size(); ++k) {
    for (std::size_t p = 0; p < 5; ++p) {
      right[p] += commanded_radps[k - p] * measured_radps[k];
      for (std::size_t q = 0; q < 5; ++q) {
        normal[p][q] += commanded_radps[k - p] * commanded_radps[k - q];
      }
    }
  }
  const std::array<double, 5> delta = solve(normal, right);
  // The table after Procedure 4.8 for h = 0.0157, con = 0. The chain gives (0.003, 0.202, 0.404,
  // 0.289, 0.102).
  const std::array<double, 5> thesis{0.0, 0.2452, 0.3742, 0.2798, 0.1008};
  for (std::size_t j = 0; j < 5; ++j) {
    EXPECT_NEAR(delta[j], thesis[j], 0.05) << "δ^" << j;
  }
}

TEST(SimMotorController, LooseEncoderLosesASeededFractionOfPulses) {
  const auto enc_after = [](std::uint64_t seed) {
    MotorController controller(0, pulse_angle(0), kPulsesPerRev, seed);
    controller.set_lost_pulse_fraction(0.25);
    controller.advance(1 * kMs, pulse_angle(10000));
    return controller.registers().enc;
  };
  EXPECT_EQ(enc_after(9), enc_after(9));
  EXPECT_NEAR(enc_after(9), 7500, 150);  // σ = √(10000·0.25·0.75) ≈ 43
  MotorController controller(0, 0.0, kPulsesPerRev, 1);
  EXPECT_THROW(controller.set_lost_pulse_fraction(-0.1), std::invalid_argument);
  EXPECT_THROW(MotorController(0, 0.0, kPulsesPerRev, 1, 3), std::invalid_argument);
  EXPECT_THROW(MotorController(8, 0.0, kPulsesPerRev, 1), std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::sim
