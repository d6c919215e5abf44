#include "sim/electrics/sim_truth.hpp"

#include <numbers>

#include "sim/electrics/seeded_random.hpp"

namespace marsokhod::sim {
namespace {

// One stream per group of draws: adding a draw to one group leaves the others unchanged.
enum Stream : std::uint64_t { kMotorStream = 1, kSensorStream = 2, kBacklashStream = 3 };

void scatter_motor(MotorTruth& motor, SeededRandom& random) {
  motor.scale *= 1.0 + random.uniform(-0.02, 0.02);
  motor.lag_time_constant_s = random.uniform(0.010, 0.014);
  motor.droop_same_sign_radps_per_nm *= 1.0 + random.uniform(-0.05, 0.05);
  motor.droop_opposite_sign_radps_per_nm *= 1.0 + random.uniform(-0.05, 0.05);
  motor.dead_zone_v *= 1.0 + random.uniform(-0.10, 0.10);
  motor.speed_per_volt_radps_per_v *= 1.0 + random.uniform(-0.01, 0.01);
}

// Offsets a conversion physical = gain·counts + offset by a few counts.
void shift_conversion(LinearConversion& conversion, SeededRandom& random, double counts) {
  conversion.offset += conversion.gain * random.uniform(-counts, counts);
}

void scatter_sensors(SensorTruth& sensors, SeededRandom& random) {
  sensors.gyro_null_base_counts += random.uniform(-5.0, 5.0);  // TYP 505 within 490..520
  sensors.gyro_drift_amplitude_counts = random.uniform(1.5, 2.5);
  // amplitude·2π/period ≤ 2.5·2π/1600 = 0.0098 LSB/s: within the datasheet's 0.01 LSB/s.
  sensors.gyro_drift_period_s = random.uniform(1600.0, 3000.0);
  sensors.gyro_drift_phase_rad = random.uniform(0.0, 2.0 * std::numbers::pi);
  for (AccelerometerAxisParams& axis : sensors.accelerometer) {
    axis.minus_g_counts += random.uniform(-2.0, 2.0);
    axis.plus_g_counts += random.uniform(-2.0, 2.0);
  }
  shift_conversion(sensors.tilt_front, random, 3.0);
  shift_conversion(sensors.tilt_rear, random, 3.0);
  // The supply's divider (300 kΩ / 68.1 kΩ, 1 % parts) and µ8's ADC reference: the gain within
  // ±1.5 %, the offset a few counts (Procedure 3.5 finds them).
  shift_conversion(sensors.supply, random, 3.0);
  sensors.supply.gain *= 1.0 + random.uniform(-0.015, 0.015);
}

// A joint's play differs from the nominal by 6–15 % either way: clearly, so that a calibration
// returning the nominal value is told apart from one that measured it.
void scatter_backlash(MotorTruth& motor, SeededRandom& random) {
  const double sign = random.uniform(-1.0, 1.0) < 0.0 ? -1.0 : 1.0;
  motor.backlash_rad *= 1.0 + sign * random.uniform(0.06, 0.15);
}

}  // namespace

SimTruth exact_sim_truth(const Params& params) {
  SimTruth truth;
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    truth.motors[i].scale = params.motors.scale[i];
    truth.motors[i].backlash_rad = params.motors.backlash_rad[i];
  }
  truth.power.brownout_v = params.power.brownout_v;
  SensorTruth& sensors = truth.sensors;
  sensors.gravity_mps2 = params.sensors.gravity_mps2;
  sensors.gyro_null_base_counts = params.sensors.gyro_null_typ_counts;
  sensors.gyro_radps_per_count = params.sensors.gyro_radps_per_count;
  sensors.accelerometer = params.sensors.accelerometer;
  sensors.tilt_front = params.sensors.tilt_front;
  sensors.tilt_rear = params.sensors.tilt_rear;
  sensors.supply = params.sensors.supply;
  return truth;
}

SimTruth make_sim_truth(const Params& params, std::uint64_t seed) {
  SimTruth truth = exact_sim_truth(params);
  truth.seed = seed;
  SeededRandom motor_random(derive_seed(seed, kMotorStream));
  for (MotorTruth& motor : truth.motors) {
    scatter_motor(motor, motor_random);
  }
  SeededRandom backlash_random(derive_seed(seed, kBacklashStream));
  for (std::size_t joint : {kFrontJoint, kRearJoint}) {
    scatter_backlash(truth.motors[joint], backlash_random);
  }
  SeededRandom sensor_random(derive_seed(seed, kSensorStream));
  scatter_sensors(truth.sensors, sensor_random);
  return truth;
}

}  // namespace marsokhod::sim
