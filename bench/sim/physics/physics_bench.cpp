// The cost of one physics step: RoverPhysics::step (joint modes, then mj_step) against a bare
// mj_step on the same generated model, and on grass (rolling friction, MuJoCo's condim 6; terrain
// 1 was the rigid contact sand had before the soil model, gone since 2026-11-29), a heightfield
// and the soft sand of
// sim/soil (terrain 3: Wong–Reece forces per wheel on a deformable grid). The counter
// real_time_factor is simulated seconds per wall-clock second. And the soil window's move
// (SoilGrid::shift on the simulator's 600 × 300 cells by 4.5 m, as when the rover nears an edge).
// BM_SoftSandTwoWide: the soft sand without the soil's AVX2 loop (sim/soil/wide.hpp).
#include <benchmark/benchmark.h>

#include <array>
#include <chrono>
#include <cmath>

#include "bare_rover.hpp"
#include "sim/physics/mujoco_model.hpp"
#include "sim/physics/rover_mjcf.hpp"
#include "sim/physics/rover_physics.hpp"
#include "sim/physics/terrain_mjcf.hpp"
#include "sim/soil/soil_grid.hpp"
#include "sim/soil/wide.hpp"

namespace marsokhod::sim {
namespace {

constexpr double kTimestepS = 0.001;

TerrainSpec terrain_for(int kind) {
  TerrainSpec terrain;
  if (kind == 1) terrain.ground = grass();  // rolling friction: MuJoCo's condim 6
  if (kind == 3) terrain.ground = sand();
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
  for (int i = 0; i < kBareSettleSteps; ++i) physics.step();
  for (auto _ : state) physics.step();
  set_real_time_factor(state);
}
BENCHMARK(BM_RoverPhysicsStep)->ArgName("terrain")->Arg(0)->Arg(1)->Arg(2)->Arg(3);

// The soft sand's step on the soil's two-wide loop alone (soil::wide::use(false)): what a
// machine without AVX2 runs, the same numbers more slowly.
void BM_SoftSandTwoWide(benchmark::State& state) {
  soil::wide::use(false);
  RoverPhysics physics(Params{}, terrain_for(3), kTimestepS);
  physics.set_drive(cruise());
  for (int i = 0; i < kBareSettleSteps; ++i) physics.step();
  for (auto _ : state) physics.step();
  soil::wide::use(true);
  set_real_time_factor(state);
}
BENCHMARK(BM_SoftSandTwoWide);

void BM_SoilWindowShift(benchmark::State& state) {
  soil::SoilGrid grid(kSoftSoilGrid, soil::dry_sand(), [](double, double) { return 0.0; });
  int direction = 1;
  for (auto _ : state) {
    grid.shift(direction * 225, 0);  // 4.5 m of 2 cm cells, back and forth
    direction = -direction;
    benchmark::DoNotOptimize(grid.cell_surface_m(0, 0));
  }
}
BENCHMARK(BM_SoilWindowShift)->Unit(benchmark::kMillisecond);

void BM_BareMjStep(benchmark::State& state) {
  BareRover rover = bare_rover(terrain_for(0), kTimestepS);
  for (auto _ : state) step_bare(rover);
  set_real_time_factor(state);
}
BENCHMARK(BM_BareMjStep);

// Where a bare mj_step's time goes on flat hard ground: MuJoCo's own stage timers (mjData's
// timer, which count only with the mjcb_time clock installed), per step in µs, and the contacts,
// constraint rows and solver iterations per step; at the 1 ms step of the simulator and at 2 ms
// (argument: the step in µs), whose real_time_factor says what a 2 ms step would buy.
mjtNum clock_us() {
  return std::chrono::duration<mjtNum, std::micro>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

void BM_MjStepStages(benchmark::State& state) {
  const double timestep_s = static_cast<double>(state.range(0)) * 1e-6;
  BareRover rover = bare_rover(terrain_for(0), timestep_s);
  const mjData& data = *rover.data;
  const auto& timer = data.timer;
  mjcb_time = clock_us;
  std::array<double, mjNTIMER> before{};
  for (int t = 0; t < mjNTIMER; ++t) before[t] = timer[t].duration;
  double contacts = 0.0, rows = 0.0, iterations = 0.0;
  for (auto _ : state) {
    step_bare(rover);
    contacts += data.ncon;
    rows += data.nefc;
    iterations += data.solver_iter;
  }
  mjcb_time = nullptr;
  const double steps = static_cast<double>(state.iterations());
  const auto per_step_us = [&](int t) { return (timer[t].duration - before[t]) / steps; };
  state.counters["step_us"] = per_step_us(mjTIMER_STEP);
  state.counters["kinematics_us"] = per_step_us(mjTIMER_POS_KINEMATICS);
  state.counters["inertia_us"] = per_step_us(mjTIMER_POS_INERTIA);
  state.counters["collision_us"] = per_step_us(mjTIMER_POS_COLLISION);
  state.counters["make_constraints_us"] = per_step_us(mjTIMER_POS_MAKE);
  state.counters["project_us"] = per_step_us(mjTIMER_POS_PROJECT);
  state.counters["position_us"] = per_step_us(mjTIMER_POSITION);
  state.counters["velocity_us"] = per_step_us(mjTIMER_VELOCITY);
  state.counters["actuation_us"] = per_step_us(mjTIMER_ACTUATION);
  state.counters["solver_us"] = per_step_us(mjTIMER_CONSTRAINT);
  state.counters["integration_us"] = per_step_us(mjTIMER_STEP) - per_step_us(mjTIMER_FORWARD);
  state.counters["contacts"] = contacts / steps;
  state.counters["constraint_rows"] = rows / steps;
  state.counters["solver_iterations"] = iterations / steps;
  int warnings = 0;
  for (const mjWarningStat& w : data.warning) warnings += w.number;
  state.counters["mujoco_warnings"] = warnings;
  state.counters["real_time_factor"] =
      benchmark::Counter(steps * timestep_s, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_MjStepStages)->ArgName("step_us")->Arg(1000)->Arg(2000);

}  // namespace
}  // namespace marsokhod::sim
