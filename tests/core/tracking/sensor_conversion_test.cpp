#include "core/tracking/sensor_conversion.hpp"

#include <limits>

#include "tracking_test_support.hpp"

namespace marsokhod::tracking {
namespace {

using ::testing::HasSubstr;
using testing::invalid_argument_message;

const SensorParams kParams{};

TEST(SensorConversion, AccelerometerAtTypReadings) {
  // (3.5) with Procedure 3.3's table at the TYP readings 279, 251, 376:
  //   a1 = 9.81·(413 + 145 − 558)/(413 − 145) = 0 exactly;
  //   a2 = 9.81·(383 + 120 − 502)/(383 − 120) = 9.81/263 = 0.0373;
  //   a3 = 9.81·(376 + 75 − 752)/(376 − 75) = −9.81 (gravity along −x3 at rest).
  EXPECT_EQ(accelerometer_mps2(279, kParams.accelerometer[0], 9.81), 0.0);
  EXPECT_NEAR(accelerometer_mps2(251, kParams.accelerometer[1], 9.81), 0.0373004, 1e-7);
  EXPECT_NEAR(accelerometer_mps2(376, kParams.accelerometer[2], 9.81), -9.81, 1e-12);
}

TEST(SensorConversion, AccelerometerEndpointsAreMinusAndPlusG) {
  // The +g reading maps to −g and the −g reading to +g on every axis, midway to 0.
  for (const AccelerometerAxisParams& axis : kParams.accelerometer) {
    EXPECT_NEAR(accelerometer_mps2(axis.plus_g_counts, axis, 9.81), -9.81, 1e-12);
    EXPECT_NEAR(accelerometer_mps2(axis.minus_g_counts, axis, 9.81), 9.81, 1e-12);
    EXPECT_NEAR(accelerometer_mps2(0.5 * (axis.plus_g_counts + axis.minus_g_counts), axis, 9.81),
                0.0, 1e-12);
  }
}

TEST(SensorConversion, ChapterTableIsTheNegationOf3Point5) {
  // The chapter 3.3 table's affine conversions (0.0732·acc − 20.42, 0.0746·acc − 18.76,
  // 0.0652·acc − 14.69) equal −(3.5) up to their printed rounding, over each axis' whole ±g span:
  // the reason (3.5) is used and the table is not.
  const std::array<LinearConversion, 3> table{
      {{0.0732, -20.42}, {0.0746, -18.76}, {0.0652, -14.69}}};
  for (std::size_t i = 0; i < 3; ++i) {
    const AccelerometerAxisParams& axis = kParams.accelerometer[i];
    for (double counts = axis.minus_g_counts; counts <= axis.plus_g_counts; counts += 1.0) {
      EXPECT_NEAR(table[i](counts), -accelerometer_mps2(counts, axis, 9.81), 0.02)
          << "axis " << i + 1 << " at " << counts;
    }
  }
}

TEST(SensorConversion, YawRate) {
  // (3.4): 0.0170·(505 − 505) = 0; a reading 10 below the null line turns at +0.17 rad/s.
  EXPECT_EQ(yaw_rate_radps(505, 505, 0.0170), 0.0);
  EXPECT_NEAR(yaw_rate_radps(495, 505, 0.0170), 0.17, 1e-12);
  EXPECT_NEAR(yaw_rate_radps(515, 505, 0.0170), -0.17, 1e-12);
}

TEST(SensorConversion, TiltAndSupplyAtTypReadings) {
  // θf = 0.00495·527 − 2.61 = −0.00135; θr = −0.00526·520 + 2.74 = +0.0048 (docs/design.md's sign);
  // U = 0.06768·970 − 41.0823 = 24.5673 V, within 1 V of the nominal 24 V.
  EXPECT_NEAR(kParams.tilt_front(527), -0.00135, 1e-9);
  EXPECT_NEAR(kParams.tilt_rear(520), 0.0048, 1e-9);
  EXPECT_NEAR(kParams.supply(970), 24.5673, 1e-9);
  EXPECT_NEAR(kParams.supply(970), 24.0, 1.0);
}

TEST(SensorConversion, DefaultsAreValid) { EXPECT_NO_THROW(validate(kParams)); }

TEST(SensorConversion, InvalidParametersNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  SensorParams params;
  params.gravity_mps2 = nan;
  EXPECT_THAT(invalid_argument_message([&] { validate(params); }),
              HasSubstr("sensors.gravity_mps2"));

  params = SensorParams{};
  params.gyro_radps_per_count = 0.0;
  EXPECT_THAT(invalid_argument_message([&] { validate(params); }),
              HasSubstr("sensors.gyro_radps_per_count"));

  params = SensorParams{};
  params.gyro_null_typ_counts = 1024.0;
  EXPECT_THAT(invalid_argument_message([&] { validate(params); }),
              HasSubstr("sensors.gyro_null_typ_counts"));

  params = SensorParams{};
  params.accelerometer[1].plus_g_counts = 120.0;  // equal to −g: (3.5) would divide by zero
  EXPECT_THAT(invalid_argument_message([&] { validate(params); }),
              HasSubstr("sensors.accelerometer_plus_g_counts[1]"));

  params = SensorParams{};
  params.accelerometer[2].minus_g_counts = nan;
  EXPECT_THAT(invalid_argument_message([&] { validate(params); }),
              HasSubstr("sensors.accelerometer_minus_g_counts[2]"));

  params = SensorParams{};
  params.tilt_rear.offset = nan;
  EXPECT_THAT(invalid_argument_message([&] { validate(params); }),
              HasSubstr("sensors.tilt_rear_offset_rad"));

  params = SensorParams{};
  params.tilt_front.gain = 0.0;
  EXPECT_THAT(invalid_argument_message([&] { validate(params); }),
              HasSubstr("sensors.tilt_front_rad_per_count"));

  params = SensorParams{};
  params.supply.gain = -0.06768;
  EXPECT_THAT(invalid_argument_message([&] { validate(params); }),
              HasSubstr("sensors.supply_v_per_count"));
}

}  // namespace
}  // namespace marsokhod::tracking
