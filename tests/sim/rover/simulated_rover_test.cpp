// The whole simulated rover through CAN frames only, as the driver meets it: physical properties
// checked with the thesis' own conversions on the frames that come back.
#include "sim/rover/simulated_rover.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/adaptation/motor_curve.hpp"
#include "core/adaptation/no_load_velocity.hpp"
#include "core/mobility/joint_compensation.hpp"
#include "core/protocol/codec.hpp"
#include "core/tracking/motor_tracker.hpp"
#include "core/tracking/sensor_conversion.hpp"

namespace marsokhod::sim {
namespace {

constexpr double kH = 0.0156;
constexpr double kPi = std::numbers::pi;

// A minimal driver stand-in: configures µ0–µ7, then sends the given duties and 0x80 every cycle
// and keeps what came back.
class Bench {
 public:
  explicit Bench(SimOptions options = {}) : rover(params, options) {
    for (std::uint8_t i = 0; i < 8; ++i) {
      rover.send(protocol::encode(protocol::ConfigurationRequest{i, 511, 0, 0}), 0.0);
    }
    run(2, {});
  }

  // `cycles` cycles at the given duties; every frame that comes back must decode.
  void run(int cycles, const MotorVector& duty, bool measure = true) {
    for (int k = 0; k < cycles; ++k) {
      for (std::uint8_t i = 0; i < 8; ++i) {
        const double d = std::clamp(duty[i], -1.0, 1.0);
        const auto pwm = static_cast<std::uint16_t>(std::lround(std::abs(d) * 511));
        rover.send(protocol::encode(protocol::ControlRequest{i, d < 0.0 && pwm > 0, true, pwm}), t);
      }
      if (measure) rover.send(protocol::encode(protocol::MeasurementRequest{}), t);
      t += kH;
      for (const TimedFrame& f : rover.advance_to(t)) take(f);
    }
  }

  Params params;
  SimulatedRover rover;
  tracking::AllMotorsTracker motors{params.motors};
  protocol::MeasurementResponse last_measurement;
  std::vector<TimedFrame> stop_frames;  // requests on the bus from µ8's dead man's switch
  int frames = 0;
  double t = 0.0;

 private:
  void take(const TimedFrame& f) {
    ++frames;
    const protocol::DecodeResult r = protocol::decode(f.frame);
    ASSERT_TRUE(r.ok()) << r.error().reason;
    if (const auto* c = std::get_if<protocol::ControlResponse>(&r.message())) {
      motors.update_motor(*c, 0);
    } else if (const auto* m = std::get_if<protocol::MeasurementResponse>(&r.message())) {
      last_measurement = *m;
    } else if (std::holds_alternative<protocol::ControlRequest>(r.message())) {
      stop_frames.push_back(f);
    }
  }
};

MotorVector wheels(double d) { return {d, d, d, d, d, d, 0.0, 0.0}; }

TEST(SimulatedRover, DrivingStraightAdvancesAtWheelSpeedTimesRadius) {
  Bench bench;
  bench.run(320, wheels(0.5));  // 5 s
  const GroundTruth before = bench.rover.truth();
  bench.run(128, wheels(0.5));  // 2 s at steady speed
  const GroundTruth after = bench.rover.truth();
  double wheel_speed = 0.0;
  for (std::size_t i = 0; i < kWheelCount; ++i) wheel_speed += bench.motors.sample().velocity_radps[i];
  wheel_speed /= kWheelCount;
  const double distance = std::hypot(after.position_m[0] - before.position_m[0],
                                     after.position_m[1] - before.position_m[1]);
  const double elapsed = 128 * kH;
  // v = ω·r with r = 0.125 m on hard ground (the blades count), within 5 %.
  EXPECT_GT(wheel_speed, 1.0);  // ≈ W(0.5) = 1.5 rad/s
  EXPECT_NEAR(distance / elapsed, wheel_speed * 0.125, 0.05 * wheel_speed * 0.125);
  EXPECT_GT(bench.frames, 448 * 9);
}

TEST(SimulatedRover, SpinShowsOnTheGyro) {
  SimOptions options;
  options.nominal_unit = true;  // the gyro's base line is the configured 505
  Bench bench(options);
  // m2 at vertical joints: F(0.387) = 2.09; left backward, right forward: counter-clockwise.
  const double f = 5.3 * 0.3867 + 0.04;
  const MotorVector spin{-0.3 * f / 2.09 * 1.0, 0.3, -0.3 / 2.09, 0.3 / 2.09, -0.3, 0.3, 0.0, 0.0};
  bench.run(256, spin);
  const auto& p = bench.params.sensors;
  const double measured =
      tracking::yaw_rate_radps(bench.last_measurement.yaw, p.gyro_null_typ_counts, p.gyro_radps_per_count);
  const double truth = bench.rover.imu().yaw_rate_radps;
  EXPECT_GT(truth, 0.05);  // turning counter-clockwise
  // One count of the gyro is 0.017 rad/s; the null rate drifts within ±2.5 counts.
  EXPECT_NEAR(measured, truth, 0.06);
}

TEST(SimulatedRover, FifteenDegreeSlopeReadsFifteenDegrees) {
  SimOptions options;
  options.nominal_unit = true;  // the configured ±g table
  options.terrain.kind = TerrainKind::kSlope;
  options.terrain.slope_rad = 15.0 * kPi / 180.0;
  Bench bench(options);
  SimFaults hold;
  hold.wheel_blocked.fill(true);  // stand still on the slope
  bench.rover.set_faults(hold);
  bench.run(64, wheels(0.0));
  std::array<double, 3> a{};
  for (std::size_t i = 0; i < 3; ++i) {
    a[i] = tracking::accelerometer_mps2(bench.last_measurement.acc[i],
                                        bench.params.sensors.accelerometer[i], 9.81);
  }
  // (3.5) returns gravity in the sensor axes: nose up by θ reads (−g sin θ, 0, −g cos θ).
  const double pitch_deg = std::atan2(-a[0], -a[2]) * 180.0 / kPi;
  EXPECT_NEAR(std::abs(pitch_deg), 15.0, 1.0);
}

TEST(SimulatedRover, BatterySagsUnderLoadAndRecovers) {
  Bench bench;
  const auto volts = [&] { return bench.params.sensors.supply(bench.last_measurement.vcc); };
  bench.run(64, wheels(0.0));
  const double rest = volts();
  SimFaults hold;
  hold.wheel_blocked.fill(true);  // stalled wheels draw heavy current
  bench.rover.set_faults(hold);
  bench.run(64, wheels(0.6));
  const double loaded = volts();
  bench.run(320, wheels(0.0));
  const double recovered = volts();
  EXPECT_LT(loaded, rest - 0.5);
  EXPECT_GT(recovered, loaded + 0.3);
  EXPECT_NEAR(recovered, rest, 0.3);
}

TEST(SimulatedRover, DeadMansSwitchStopsTheMotorsOnTime) {
  Bench bench;
  bench.rover.send(protocol::encode(protocol::DeadManRequest{4}), bench.t);
  bench.run(64, wheels(0.4));  // driving, with 0x80 every cycle
  const double last_request = bench.t - kH;
  bench.run(100, wheels(0.4), /*measure=*/false);  // the driver stops feeding µ8
  // 0.262144·dog s after the last 0x80 (plus the bus time of the frames before each stop), and
  // again every 0.262144 s while µ8 hears no 0x80: at 1.05 s, 1.31 s, and 1.57 s (cut short).
  ASSERT_GT(bench.stop_frames.size(), 16u);
  ASSERT_LT(bench.stop_frames.size(), 24u);
  for (std::size_t k = 0; k < 16; ++k) {
    const double deadline = last_request + static_cast<double>(4 + k / 8) * 0.262144;
    EXPECT_GE(bench.stop_frames[k].time_s, deadline) << k;
    // The bus is shared with the (halted driver's stand-in's) control requests: within 5 ms.
    EXPECT_LT(bench.stop_frames[k].time_s, deadline + 0.005) << k;
  }
  for (const TimedFrame& f : bench.stop_frames) {
    const auto m = std::get<protocol::ControlRequest>(protocol::decode(f.frame).message());
    EXPECT_EQ(m.pwm, 0);
  }
}

TEST(SimulatedRover, JointCompensationSlipsTheWheelsFarLess) {
  // Bend the front joint at d6 = −0.25 for 2 s, once with the wheels still and once with
  // n6·w6 of (5.1) (ρf = 0.5) on them: per radian the joint bends, the compensated wheels slip
  // far less (uncompensated, the braked wheels also hold the joint back).
  auto slip_while_bending = [](bool compensate) {
    Bench bench;
    const adaptation::MotorCurve curve(bench.params.motor_curves.front());
    double slip = 0.0;
    const double start = bench.rover.truth().joint_angle_rad[kFrontJoint];
    for (int k = 0; k < 128; ++k) {
      MotorVector d{};
      d[kFrontJoint] = -0.25;
      if (compensate) {
        const double p6 = bench.motors.sample().position_rad[kFrontJoint];
        const double w6 = bench.motors.sample().velocity_radps[kFrontJoint];
        const MotorVector n6 = mobility::front_joint_compensation(p6, 0.5, bench.params.geometry);
        for (std::size_t i = 0; i < kWheelCount; ++i) {
          d[i] = adaptation::duty_for_no_load_velocity(curve, n6[i] * w6, bench.params.motors.scale[i],
                                                       24.0, 24.0);
        }
      }
      bench.run(1, d);
      for (double s : bench.rover.truth().wheel_slip_mps) slip += std::abs(s) * kH;
    }
    const double bent = std::abs(bench.rover.truth().joint_angle_rad[kFrontJoint] - start);
    EXPECT_GT(bent, 0.1);
    return slip / bent;
  };
  const double without = slip_while_bending(false);
  const double with = slip_while_bending(true);
  EXPECT_LT(with, 0.5 * without) << "with " << with << " m/rad, without " << without << " m/rad";
}

TEST(SimulatedRover, BrownOutSilencesTheBusAndTheDeadMansSwitchStops) {
  Bench bench;
  bench.rover.send(protocol::encode(protocol::DeadManRequest{4}), bench.t);
  bench.run(64, wheels(0.4));
  const int before = bench.frames;
  bench.rover.force_brownout();
  bench.run(128, wheels(0.4));  // 2 s: more than 0.262144·4 s
  EXPECT_FALSE(bench.rover.computer_on());
  EXPECT_EQ(bench.frames, before);  // nothing reached the driver side
  EXPECT_GT(bench.rover.frames_dropped_during_brownout(), 0u);
  for (std::size_t i = 0; i < kMotorCount; ++i) EXPECT_EQ(bench.rover.firmware().duty()[i], 0.0);
  // After the reboot time (30 s) the computer is back and the bus answers again.
  bench.run(static_cast<int>(30.0 / kH), wheels(0.0));
  EXPECT_TRUE(bench.rover.computer_on());
  EXPECT_GT(bench.frames, before);
}

TEST(SimulatedRover, AJointPushedAndReleasedHoldsWhileTheWheelsDrive) {
  // Not back-drivable (chapter 5.3's lock): after the front joint motor pushed and stopped, the
  // wheels' forces while driving must not move the joint.
  Bench bench;
  MotorVector push{};
  push[kFrontJoint] = -0.08;
  bench.run(100, push);
  bench.run(20, wheels(0.0));
  const double held = bench.rover.truth().joint_angle_rad[kFrontJoint];
  bench.run(250, wheels(0.5));
  EXPECT_NEAR(bench.rover.truth().joint_angle_rad[kFrontJoint], held, 0.002);
}

TEST(SimulatedRover, TwoRunsWithOneSeedAreIdentical) {
  auto run = [] {
    SimOptions options;
    options.seed = 7;
    Bench bench(options);
    bench.run(100, wheels(0.3));
    return std::make_pair(bench.rover.truth().position_m, bench.last_measurement);
  };
  const auto a = run();
  const auto b = run();
  EXPECT_EQ(a.first, b.first);
  EXPECT_EQ(a.second, b.second);
}

TEST(SimulatedRover, FaultValuesAreChecked) {
  Params params;
  SimulatedRover rover(params, {});
  SimFaults bad;
  bad.frame_loss_probability = 1.5;
  EXPECT_THROW(rover.set_faults(bad), std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::sim
