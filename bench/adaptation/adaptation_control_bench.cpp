// The per-cycle cost of chapter 4 for all 8 motors: backlash (4.1)/(4.2), the no-load estimate
// (4.4) and load, (4.3) both ways, and the control laws (4.14)–(4.16).
#include <benchmark/benchmark.h>

#include <cmath>

#include "core/adaptation/backlash.hpp"
#include "core/adaptation/motor_curve.hpp"
#include "core/adaptation/no_load_estimator.hpp"
#include "core/adaptation/no_load_velocity.hpp"
#include "core/control/bounded_velocity_control.hpp"
#include "core/control/position_control.hpp"
#include "core/control/velocity_control.hpp"

namespace marsokhod {
namespace {

void BM_AdaptationAndControlCycle(benchmark::State& state) {
  const Params params;
  adaptation::RoverBacklashTracker backlash(params.motors);
  const adaptation::MotorCurve curve(params.motor_curves.front());
  adaptation::NoLoadEstimator estimator(
      adaptation::select_response(params.responses, params.cycle.period_s, params.cycle.con));
  const control::ControlParams joint = control::joint_control_params(params);
  const control::ControlParams drive{params.operator_input.drive_rate_per_s,
                                     params.motors.max_no_load_speed_radps,
                                     params.cycle.period_s};
  MotorVector motor_position = params.motors.initial_position_rad;
  MotorVector motor_velocity{};
  MotorVector duty{};
  double drive_velocity = 0.0;
  control::MotionState front{-1.2121, 0.0};
  control::MotionState rear{1.2121, 0.0};
  long k = 0;
  for (auto _ : state) {
    // Plausible measurements that change every cycle.
    const double phase = 0.01 * static_cast<double>(++k % 1000);
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      motor_velocity[i] = 0.8 * std::sin(phase + static_cast<double>(i));
      motor_position[i] += motor_velocity[i] * params.cycle.period_s;
    }
    backlash.update(motor_position, motor_velocity);
    const MotorVector w = backlash.joint_velocity_radps();
    MotorVector w_hat{};
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      w_hat[i] = adaptation::no_load_velocity(curve, duty[i], params.motors.scale[i], 23.5, 24.0);
    }
    const MotorVector nu = estimator.no_load_velocity_radps();
    const MotorVector load = adaptation::load(w, nu);
    estimator.push(w_hat);
    const double c_drive = control::velocity_control(drive_velocity, 1.5, drive);
    drive_velocity = control::step({0.0, drive_velocity}, c_drive, drive).velocity;
    const double c_front = control::position_velocity_control(front, {-2.21, 0.0}, joint);
    front = control::step(front, c_front, joint);
    const double c_rear = control::bounded_velocity_control(rear, 0.3, 1.2121, 2.55, joint);
    rear = control::step(rear, c_rear, joint);
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      const double wanted = i < kWheelCount ? drive_velocity : (i == 6 ? front.velocity : rear.velocity);
      duty[i] = adaptation::duty_for_no_load_velocity(curve, wanted, params.motors.scale[i], 23.5, 24.0);
    }
    benchmark::DoNotOptimize(load);
    benchmark::DoNotOptimize(duty);
  }
}
BENCHMARK(BM_AdaptationAndControlCycle);

}  // namespace
}  // namespace marsokhod
