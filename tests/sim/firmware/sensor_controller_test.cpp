#include "sim/firmware/sensor_controller.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <variant>

#include "core/protocol/codec.hpp"
#include "core/tracking/sensor_tracker.hpp"

namespace marsokhod::sim {
namespace {

constexpr SimTimeNs kMs = 1'000'000;

SensorTruthSample typical_state() {
  SensorTruthSample sample;  // flat, at rest, joints equally inclined
  sample.supply_v = 24.57;
  return sample;
}

protocol::MeasurementRequest request_with(const char* text, bool green, bool white) {
  protocol::MeasurementRequest request;
  request.led0 = green;
  request.led1 = white;
  for (std::size_t i = 0; i < request.lcd.size(); ++i) {
    request.lcd[i] = text[i];
  }
  return request;
}

protocol::MeasurementResponse measure_at(SensorController& sensor, SimTimeNs time_ns,
                                         const SensorTruthSample& sample) {
  sensor.advance(time_ns, sample);
  const auto frame = sensor.receive(protocol::encode(protocol::MeasurementRequest{}));
  EXPECT_TRUE(frame.has_value());
  const protocol::DecodeResult decoded = protocol::decode(*frame);
  EXPECT_TRUE(decoded.ok());
  return std::get<protocol::MeasurementResponse>(decoded.message());
}

TEST(SimSensorController, TypicalStateConvertsBackToTheTruth) {
  const Params params;
  SensorController sensor(exact_sim_truth(params).sensors, 4, typical_state());
  tracking::SensorTracker tracker(params.sensors, params.filters);
  double accel_sum_mps2 = 0.0;
  double supply_sum_v = 0.0;
  constexpr int kCycles = 200;
  for (int k = 0; k < kCycles; ++k) {
    const tracking::SensorState& state =
        tracker.update(measure_at(sensor, SimTimeNs{k} * 15'600'000, typical_state()), true, true);
    // One reading: within quantisation (½ LSB) plus 5σ of noise (gyro: and 0.1 LSB of drift).
    EXPECT_LE(std::abs(state.yaw_rate_radps), 0.0170 * (0.5 + 5 * 0.4 + 0.1));
    EXPECT_LE(std::abs(state.accel_mps2[0]), 0.0732 * (0.5 + 5 * 0.7));
    EXPECT_LE(std::abs(state.accel_mps2[2] + 9.81), 0.0652 * (0.5 + 5 * 0.7));
    EXPECT_LE(std::abs(state.supply_v - 24.57), 0.06768 * (0.5 + 5 * 0.3));
    accel_sum_mps2 += state.accel_mps2[2];
    supply_sum_v += state.supply_v;
  }
  // Averages: the noise shrinks by √200; what remains is the ½-count of acc² = 251.5 and vcc.
  EXPECT_NEAR(accel_sum_mps2 / kCycles, -9.81, 0.03);
  EXPECT_NEAR(supply_sum_v / kCycles, 24.57, 0.02);
  EXPECT_TRUE(tracker.state().front_tilt_seen && tracker.state().rear_tilt_seen);
  EXPECT_NEAR(tracker.state().front_tilt_rad, 0.0, 0.00495 * 2.0);
  EXPECT_NEAR(tracker.state().rear_tilt_rad, 0.0, 0.00526 * 2.0);
}

TEST(SimSensorController, TiltChannelAlternatesFrontFirst) {
  SensorController sensor(exact_sim_truth(Params{}).sensors, 1, typical_state());
  for (int k = 0; k < 6; ++k) {
    EXPECT_EQ(measure_at(sensor, k * kMs, typical_state()).tilt_channel,
              k % 2 == 0 ? protocol::TiltChannel::kFront : protocol::TiltChannel::kRear);
  }
}

TEST(SimSensorController, YawRateAndTiltReachTheReadings) {
  SensorTruth truth = exact_sim_truth(Params{}).sensors;
  truth.gyro_noise_counts = 0.0;
  truth.tilt_noise_counts = 0.0;
  SensorController sensor(truth, 1, typical_state());
  SensorTruthSample turning = typical_state();
  turning.yaw_rate_radps = 0.34;  // 20 counts below the null rate
  turning.front_tilt_rad = 0.3;   // beyond the ±4° play: the pot reads 0.3 − 0.0698
  const protocol::MeasurementResponse response = measure_at(sensor, kMs, turning);
  EXPECT_EQ(response.yaw, 485);
  EXPECT_EQ(response.tlt, quantise_adc((0.3 - 4.0 * std::numbers::pi / 180.0 + 2.61) / 0.00495));
}

TEST(SimSensorController, StoresLcdAndLeds) {
  SensorController sensor(exact_sim_truth(Params{}).sensors, 1, typical_state());
  EXPECT_EQ(sensor.lcd_display(), kLcdIdleText);  // the bus has been silent so far
  sensor.advance(kMs, typical_state());
  ASSERT_TRUE(sensor.receive(protocol::encode(request_with("Rolking ", true, false))));
  EXPECT_TRUE(sensor.green_led());
  EXPECT_FALSE(sensor.white_led());
  const std::string display = sensor.lcd_display();
  EXPECT_EQ(display.size(), 16U);
  EXPECT_EQ(display.substr(0, 8), "Rolking ");
  EXPECT_NE(display.find("24."), std::string::npos);
  sensor.advance(kMs + 1'000'000'001, typical_state());
  EXPECT_EQ(sensor.lcd_display(), kLcdIdleText);
}

TEST(SimSensorController, DeadManDeadlineIsDogPeriodsAfterTheLastMeasurementRequest) {
  SensorController sensor(exact_sim_truth(Params{}).sensors, 1, typical_state());
  EXPECT_FALSE(sensor.dead_man_deadline_ns());  // disabled by default
  sensor.advance(5 * kMs, typical_state());
  const auto answer = sensor.receive(protocol::encode(protocol::DeadManRequest{4}));
  ASSERT_TRUE(answer);
  EXPECT_TRUE(
      std::holds_alternative<protocol::DeadManResponse>(protocol::decode(*answer).message()));
  // Arming restarts the timer: 5 ms + 4·0.262144 s.
  EXPECT_EQ(*sensor.dead_man_deadline_ns(), 5 * kMs + 4 * 262'144'000);
  sensor.advance(100 * kMs, typical_state());
  sensor.receive(protocol::encode(protocol::MeasurementRequest{}));
  EXPECT_EQ(*sensor.dead_man_deadline_ns(), 100 * kMs + 1'048'576'000);
  const std::array<protocol::CanFrame, 8> stops = sensor.fire_dead_man();
  for (std::uint8_t node = 0; node < 8; ++node) {
    const protocol::DecodeResult decoded = protocol::decode(stops[node]);
    ASSERT_TRUE(decoded.ok());
    EXPECT_EQ(std::get<protocol::ControlRequest>(decoded.message()),
              (protocol::ControlRequest{node, false, true, 0}));
  }
  // Again every tick while the silence lasts; the silence counts once.
  EXPECT_EQ(*sensor.dead_man_deadline_ns(), 100 * kMs + 1'310'720'000);
  EXPECT_EQ(sensor.fire_dead_man(), stops);
  EXPECT_EQ(*sensor.dead_man_deadline_ns(), 100 * kMs + 1'572'864'000);
  EXPECT_EQ(sensor.dead_man_stops(), 1U);
  EXPECT_EQ(sensor.dead_man_firings(), 2U);
  sensor.advance(2000 * kMs, typical_state());
  sensor.receive(protocol::encode(protocol::MeasurementRequest{}));
  EXPECT_EQ(*sensor.dead_man_deadline_ns(), 2000 * kMs + 1'048'576'000);
  sensor.receive(protocol::encode(protocol::DeadManRequest{0}));
  EXPECT_FALSE(sensor.dead_man_deadline_ns());
}

TEST(SimSensorController, IgnoresFramesForOthers) {
  SensorController sensor(exact_sim_truth(Params{}).sensors, 1, typical_state());
  EXPECT_FALSE(sensor.receive(protocol::encode(protocol::ControlRequest{1, false, true, 10})));
  EXPECT_FALSE(sensor.receive(protocol::encode(protocol::MeasurementResponse{})));
  protocol::CanFrame short_frame = protocol::encode(protocol::MeasurementRequest{});
  short_frame.dlc = 7;
  EXPECT_FALSE(sensor.receive(short_frame));
}

}  // namespace
}  // namespace marsokhod::sim
