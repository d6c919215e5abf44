#include "core/tracking/sensor_tracker.hpp"

#include <limits>

#include "tracking_test_support.hpp"

namespace marsokhod::tracking {
namespace {

using protocol::MeasurementResponse;
using protocol::TiltChannel;
using testing::invalid_argument_message;

// µ8's TYP readings of chapter 3.3: the rover at rest on flat ground, joints equally inclined.
MeasurementResponse typ_response(TiltChannel channel) {
  MeasurementResponse response;
  response.yaw = 505;
  response.acc = {279, 251, 376};
  response.tlt = channel == TiltChannel::kFront ? 527 : 520;
  response.vcc = 970;
  response.tilt_channel = channel;
  return response;
}

TEST(SensorTracker, TypReadingsConvertToRestOnFlatGround) {
  // ω3 = 0.0170·(505 − 505) = 0; a = (0, 9.81/263 = 0.0373, −9.81); θf = 0.00495·527 − 2.61 =
  // −0.00135; θr = −0.00526·520 + 2.74 = +0.0048; U = 0.06768·970 − 41.0823 = 24.5673 V = Ū.
  SensorTracker tracker(SensorParams{}, FilterParams{});
  tracker.update(typ_response(TiltChannel::kFront), true, true);
  const SensorState& state = tracker.update(typ_response(TiltChannel::kRear), true, true);
  EXPECT_EQ(state.yaw_rate_radps, 0.0);
  EXPECT_EQ(state.accel_mps2[0], 0.0);
  EXPECT_NEAR(state.accel_mps2[1], 0.0373, 1e-4);
  EXPECT_NEAR(state.accel_mps2[2], -9.81, 1e-12);
  EXPECT_NEAR(state.front_tilt_rad, -0.00135, 1e-9);
  EXPECT_NEAR(state.rear_tilt_rad, 0.0048, 1e-9);
  EXPECT_NEAR(state.supply_v, 24.5673, 1e-9);
  EXPECT_NEAR(state.supply_v, 24.0, 1.0);
  EXPECT_NEAR(state.reference_supply_v, 24.5673, 1e-9);
  EXPECT_DOUBLE_EQ(state.gyro_null_counts, 505.0);
  EXPECT_EQ(state.update_count, 2U);
}

TEST(SensorTracker, TiltChannelsAlternateAndKeepTheLatest) {
  SensorTracker tracker(SensorParams{}, FilterParams{});
  EXPECT_FALSE(tracker.state().front_tilt_seen);
  EXPECT_FALSE(tracker.state().rear_tilt_seen);

  MeasurementResponse response = typ_response(TiltChannel::kFront);
  response.tlt = 600;  // θf = 0.00495·600 − 2.61 = 0.36
  tracker.update(response, true, true);
  EXPECT_TRUE(tracker.state().front_tilt_seen);
  EXPECT_FALSE(tracker.state().rear_tilt_seen);
  EXPECT_NEAR(tracker.state().front_tilt_rad, 0.36, 1e-12);

  response = typ_response(TiltChannel::kRear);
  response.tlt = 450;  // θr = −0.00526·450 + 2.74 = 0.373
  tracker.update(response, true, true);
  EXPECT_TRUE(tracker.state().rear_tilt_seen);
  EXPECT_NEAR(tracker.state().rear_tilt_rad, 0.373, 1e-12);
  EXPECT_NEAR(tracker.state().front_tilt_rad, 0.36, 1e-12);  // held from the previous cycle
  EXPECT_EQ(tracker.state().latest_tilt_channel, TiltChannel::kRear);

  response = typ_response(TiltChannel::kFront);  // tltᶠ 527 → −0.00135; θr stays 0.373
  tracker.update(response, true, true);
  EXPECT_NEAR(tracker.state().front_tilt_rad, -0.00135, 1e-9);
  EXPECT_NEAR(tracker.state().rear_tilt_rad, 0.373, 1e-12);
}

TEST(SensorTracker, GyroNullLearnsOnlyWhileStill) {
  // λ = 0.99. Still with yaw 507: ω3 uses y⁰ = 505: 0.0170·(505 − 507) = −0.034 rad/s. The
  // filter starts as a mean (gyro_null.hpp): y¹ = (505 + 507)/2 = 506, and ω3 = 0.0170·(506 − 507)
  // = −0.017 rad/s next cycle; then y² = 506 + (507 − 506)/3 = 506.333.
  SensorTracker tracker(SensorParams{}, FilterParams{});
  MeasurementResponse response = typ_response(TiltChannel::kFront);
  response.yaw = 507;
  EXPECT_NEAR(tracker.update(response, true, true).yaw_rate_radps, -0.034, 1e-12);
  EXPECT_NEAR(tracker.state().gyro_null_counts, 506.0, 1e-12);
  EXPECT_NEAR(tracker.update(response, true, true).yaw_rate_radps, -0.017, 1e-12);
  EXPECT_NEAR(tracker.state().gyro_null_counts, 506.0 + 1.0 / 3.0, 1e-12);
  const double learnt_counts = tracker.state().gyro_null_counts;

  // Turning on the spot (yaw 480, 0.0170·(506.33 − 480) = 0.448 rad/s): y is held.
  response.yaw = 480;
  for (int k = 0; k < 20; ++k) {
    const SensorState& state = tracker.update(response, false, false);
    EXPECT_DOUBLE_EQ(state.gyro_null_counts, learnt_counts);
    EXPECT_NEAR(state.yaw_rate_radps, 0.0170 * (learnt_counts - 480.0), 1e-12);
  }
}

TEST(SensorTracker, ReferenceVoltageHoldsUnderLoadAndDecaysAtRest) {
  // vcc 970 → 24.5673 V for the 16 readings of Ū's warm-up (Procedure 3.5); driving, vcc 950 →
  // 23.2137 V: Ū stays 24.5673 ≥ U. At rest with all d_i = 0 at 23.2137 V:
  // Ū = 0.99·24.5673 + 0.01·23.2137 = 24.55376.
  SensorTracker tracker(SensorParams{}, FilterParams{});
  for (std::size_t k = 0; k < kSupplyAveragingReadings; ++k) {
    tracker.update(typ_response(k % 2 == 0 ? TiltChannel::kFront : TiltChannel::kRear), true,
                   true);
  }
  MeasurementResponse response = typ_response(TiltChannel::kRear);
  response.vcc = 950;
  const SensorState& driving = tracker.update(response, false, false);
  EXPECT_NEAR(driving.supply_v, 23.2137, 1e-9);
  EXPECT_NEAR(driving.reference_supply_v, 24.5673, 1e-9);
  const SensorState& resting = tracker.update(response, true, true);
  EXPECT_NEAR(resting.reference_supply_v, 0.99 * 24.5673 + 0.01 * 23.2137, 1e-9);
  EXPECT_GE(resting.reference_supply_v, resting.supply_v);
}

TEST(SensorTracker, RejectsReadingsBeyondTenBitsWithoutChange) {
  SensorTracker tracker(SensorParams{}, FilterParams{});
  tracker.update(typ_response(TiltChannel::kFront), true, true);
  MeasurementResponse response = typ_response(TiltChannel::kRear);
  response.vcc = 1024;
  EXPECT_THAT(invalid_argument_message([&] { tracker.update(response, true, true); }),
              ::testing::HasSubstr("vcc = 1024"));
  EXPECT_EQ(tracker.state().update_count, 1U);
  EXPECT_FALSE(tracker.state().rear_tilt_seen);
}

TEST(SensorTracker, RejectsInvalidParametersByName) {
  SensorParams sensors;
  sensors.gravity_mps2 = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(invalid_argument_message([&] { SensorTracker(sensors, FilterParams{}); }),
              ::testing::HasSubstr("sensors.gravity_mps2"));
  FilterParams filters;
  filters.reference_voltage_lambda = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(invalid_argument_message([&] { SensorTracker(SensorParams{}, filters); }),
              ::testing::HasSubstr("filters.reference_voltage_lambda"));
}

}  // namespace
}  // namespace marsokhod::tracking
