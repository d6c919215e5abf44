// The cost of one physics step: RoverPhysics::step (joint modes, then mj_step) against a bare
// mj_step on the same generated model, and on sand, a heightfield and the soft sand of
// sim/soil (terrain 3: Wong–Reece forces per wheel on a deformable grid). The counter
// real_time_factor is simulated seconds per wall-clock second.
#include <benchmark/benchmark.h>

#include <cmath>

#include "sim/physics/mujoco_model.hpp"
#include "sim/physics/rover_mjcf.hpp"
#include "sim/physics/rover_physics.hpp"

namespace marsokhod::sim {
namespace {

constexpr double kTimestepS = 0.001;
constexpr int kSettleSteps = 300;

MotorDrive cruise() {
  MotorDrive drive;
  for (std::size_t motor = 0; motor < kMotorCount; ++motor) {
    drive.no_load_speed_radps[motor] = motor < kWheelCount ? 2.0 : 0.0;
    drive.droop_radps_per_nm[motor] = 0.030;
    drive.stall_torque_nm[motor] = 94.0;
  }
  return drive;
}

TerrainSpec terrain_for(int kind) {
  TerrainSpec terrain;
  if (kind == 1) terrain.ground = sand();
  if (kind == 3) terrain.ground = soft_sand();
  if (kind == 2) {
    // Gentle dunes on a 64 × 64 grid over 8 m × 8 m, up to 0.2 m.
    terrain.kind = TerrainKind::kHeightfield;
    terrain.heightfield.image.width = terrain.heightfield.image.height = 64;
    for (int row = 0; row < 64; ++row) {
      for (int column = 0; column < 64; ++column) {
        terrain.heightfield.image.values.push_back(0.5 + 0.5 * std::sin(row * 0.3) *
                                                             std::cos(column * 0.2));
      }
    }
    terrain.heightfield.size_x_m = terrain.heightfield.size_y_m = 8.0;
    terrain.heightfield.max_height_m = 0.2;
  }
  return terrain;
}

void set_real_time_factor(benchmark::State& state) {
  state.counters["real_time_factor"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * kTimestepS, benchmark::Counter::kIsRate);
}

void BM_RoverPhysicsStep(benchmark::State& state) {
  RoverPhysics physics(Params{}, terrain_for(static_cast<int>(state.range(0))), kTimestepS);
  physics.set_drive(cruise());
  for (int i = 0; i < kSettleSteps; ++i) physics.step();
  for (auto _ : state) physics.step();
  set_real_time_factor(state);
}
BENCHMARK(BM_RoverPhysicsStep)->ArgName("terrain")->Arg(0)->Arg(1)->Arg(2)->Arg(3);

// The same model stepped by MuJoCo alone: the wheels' servos and the joints' locks set once, as
// RoverPhysics sets them, the rover placed on the ground.
void BM_BareMjStep(benchmark::State& state) {
  const Params params;
  const ModelPtr model = load_rover_model(params, terrain_for(0), kTimestepS);
  const DataPtr data(mj_makeData(model.get()));
  const MotorDrive drive = cruise();
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    const int actuator = require_id(*model, mjOBJ_ACTUATOR, motor_actuator_name(wheel));
    model->actuator_gainprm[actuator * mjNGAIN] = 1.0 / drive.droop_radps_per_nm[wheel];
    model->actuator_biasprm[actuator * mjNBIAS + 2] = -1.0 / drive.droop_radps_per_nm[wheel];
    model->actuator_forcerange[actuator * 2] = -drive.stall_torque_nm[wheel];
    model->actuator_forcerange[actuator * 2 + 1] = drive.stall_torque_nm[wheel];
    data->ctrl[actuator] = drive.no_load_speed_radps[wheel];
  }
  for (std::size_t motor : {kFrontJoint, kRearJoint}) {
    model->eq_active[require_id(*model, mjOBJ_EQUALITY, joint_lock_name(motor))] = 1;
  }
  data->qpos[2] = params.geometry.wheel_radius_m + 0.005;
  for (int i = 0; i < kSettleSteps; ++i) mj_step(model.get(), data.get());
  for (auto _ : state) mj_step(model.get(), data.get());
  set_real_time_factor(state);
}
BENCHMARK(BM_BareMjStep);

}  // namespace
}  // namespace marsokhod::sim
