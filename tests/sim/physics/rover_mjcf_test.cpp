#include "sim/physics/rover_mjcf.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/physics/mujoco_model.hpp"

namespace marsokhod::sim {
namespace {

TerrainSpec every_kind(TerrainKind kind) {
  TerrainSpec terrain;
  terrain.kind = kind;
  terrain.slope_rad = 0.2;
  if (kind == TerrainKind::kObstacles) terrain.obstacles.push_back(Obstacle{});
  terrain.heightfield.image = GrayImage{2, 2, {0.0, 0.25, 0.5, 1.0}};
  return terrain;
}

TEST(RoverMjcf, SameInputSameBytes) {
  EXPECT_EQ(rover_mjcf(Params{}, TerrainSpec{}, 0.001), rover_mjcf(Params{}, TerrainSpec{}, 0.001));
}

TEST(RoverMjcf, CompilesOnEveryTerrainKind) {
  for (TerrainKind kind : {TerrainKind::kFlat, TerrainKind::kSlope, TerrainKind::kObstacles,
                           TerrainKind::kHeightfield}) {
    SCOPED_TRACE(to_string(kind));
    const ModelPtr model = load_rover_model(Params{}, every_kind(kind), 0.001);
    EXPECT_EQ(model->opt.integrator, mjINT_EULER);
    EXPECT_DOUBLE_EQ(model->opt.timestep, 0.001);
    EXPECT_EQ(model->nu, static_cast<int>(kMotorCount));
  }
}

// The six wheels driven on their speed–torque lines (ω0 = 2 rad/s, droop 0.03 rad/s per N·m,
// stall 30 N·m: clipped while they spin up), the joints locked, from standing on flat ground; the
// wheels' speeds after `steps` ms. `lines_as_damping`: each wheel's kv also in its dof's damping;
// `cancelled`: the damping's force cancelled by an applied one, as RoverPhysics::apply_motor_lines
// does.
std::array<double, kWheelCount> wheel_speeds_after(int integrator, bool lines_as_damping,
                                                   bool cancelled, int steps) {
  const ModelPtr model = load_rover_model(Params{}, TerrainSpec{}, 0.001);
  mjModel& m = *model;
  m.opt.integrator = integrator;
  const DataPtr data(mj_makeData(&m));
  mjData& d = *data;
  constexpr double kv = 1.0 / 0.030;
  std::array<int, kWheelCount> dofs{};
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    const int actuator = require_id(m, mjOBJ_ACTUATOR, motor_actuator_name(wheel));
    m.actuator_gainprm[actuator * mjNGAIN] = kv;
    m.actuator_biasprm[actuator * mjNBIAS + 2] = -kv;
    m.actuator_forcerange[actuator * 2] = -30.0;
    m.actuator_forcerange[actuator * 2 + 1] = 30.0;
    d.ctrl[actuator] = 2.0;
    dofs[wheel] = m.jnt_dofadr[require_id(m, mjOBJ_JOINT, wheel_name(wheel))];
    if (lines_as_damping) m.dof_damping[dofs[wheel]] = kv;
  }
  for (std::size_t motor : {kFrontJoint, kRearJoint}) {
    m.eq_active[require_id(m, mjOBJ_EQUALITY, joint_lock_name(motor))] = 1;
  }
  d.qpos[2] = Params{}.geometry.wheel_radius_m + 0.005;
  for (int i = 0; i < steps; ++i) {
    if (lines_as_damping && cancelled) {
      for (int dof : dofs) d.qfrc_applied[dof] = kv * d.qvel[dof];
    }
    mj_step(&m, &d);
  }
  std::array<double, kWheelCount> speeds{};
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) speeds[wheel] = d.qvel[dofs[wheel]];
  return speeds;
}

// The model's Euler integrator with the lines as damping makes the step of MuJoCo's "implicit"
// integrator, which differentiates the lines (and, besides, the Coriolis forces, small here):
// through the clipped spin-up and at the steady speed the wheels agree within 1e-3 rad/s. Without
// the applied force that cancels it, the damping would act beside the line and halve the speed.
TEST(RoverMjcf, EulerWithTheLinesAsDampingStepsAsTheImplicitIntegrator) {
  for (int steps : {20, 100, 600}) {
    SCOPED_TRACE(steps);
    const auto implicit = wheel_speeds_after(mjINT_IMPLICIT, false, false, steps);
    const auto euler = wheel_speeds_after(mjINT_EULER, true, true, steps);
    for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
      EXPECT_NEAR(euler[wheel], implicit[wheel], 1e-3) << kMotorNames[wheel];
    }
  }
  const auto implicit = wheel_speeds_after(mjINT_IMPLICIT, false, false, 600);
  const auto uncancelled = wheel_speeds_after(mjINT_EULER, true, false, 600);
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    EXPECT_GT(implicit[wheel], 1.8) << kMotorNames[wheel];  // near ω0, rolling freely
    EXPECT_LT(uncancelled[wheel], 1.1) << kMotorNames[wheel];  // ≈ ω0/2
  }
}

TEST(RoverMjcf, MassBudgetOfARealisticRover) {
  const ModelPtr model = load_rover_model(Params{}, TerrainSpec{}, 0.001);
  double total_kg = 0.0;
  for (int body = 0; body < model->nbody; ++body) total_kg += model->body_mass[body];
  const double expected_kg = kCenterUnitMassKg + 2 * (kStrutMassKg + kLeverMassKg + kAxleMassKg) +
                             6 * kWheelMassKg + 2 * kShaftMassKg;
  EXPECT_NEAR(total_kg, expected_kg, 1e-9);
  EXPECT_GE(total_kg, 70.0);
  EXPECT_LE(total_kg, 100.0);
}

// Figure 3.3 laid out: with the joints vertical the exterior axles sit level with the center axle,
// sqrt(b² − a²) ahead and behind, on a track of 0.70 m.
TEST(RoverMjcf, GeometryFromParams) {
  const ModelPtr model = load_rover_model(Params{}, TerrainSpec{}, 0.001);
  const DataPtr data(mj_makeData(model.get()));
  mj_kinematics(model.get(), data.get());
  const auto wheel = [&](std::size_t index) {
    return data->xpos + 3 * require_id(*model, mjOBJ_BODY, wheel_name(index));
  };
  const double reach_m = std::sqrt(0.413 * 0.413 - 0.145 * 0.145);
  const mjtNum* center = data->xpos + 3 * require_id(*model, mjOBJ_BODY, kCenterUnitName);
  EXPECT_NEAR(wheel(kFrontLeft)[0] - center[0], reach_m, 1e-9);
  EXPECT_NEAR(wheel(kBackRight)[0] - center[0], -reach_m, 1e-9);
  EXPECT_NEAR(wheel(kFrontLeft)[2], center[2], 1e-9);
  EXPECT_NEAR(wheel(kBackRight)[2], center[2], 1e-9);
  EXPECT_NEAR(wheel(kCenterLeft)[1] - wheel(kCenterRight)[1], 0.70, 1e-12);
  // The joints' hinge values are the thesis' p6 = −γf, p7 = +γr.
  const int front = require_id(*model, mjOBJ_JOINT, joint_hinge_name(kFrontJoint));
  const int rear = require_id(*model, mjOBJ_JOINT, joint_hinge_name(kRearJoint));
  EXPECT_NEAR(model->qpos0[model->jnt_qposadr[front]], -1.2121, 1e-4);
  EXPECT_NEAR(model->qpos0[model->jnt_qposadr[rear]], 1.2121, 1e-4);
}

TEST(RoverMjcf, ExtendingAJointMovesItsAxleAway) {
  const ModelPtr model = load_rover_model(Params{}, TerrainSpec{}, 0.001);
  const DataPtr data(mj_makeData(model.get()));
  const int front = require_id(*model, mjOBJ_JOINT, joint_hinge_name(kFrontJoint));
  const int rear = require_id(*model, mjOBJ_JOINT, joint_hinge_name(kRearJoint));
  data->qpos[model->jnt_qposadr[front]] = -2.55;  // γf = 2.55
  data->qpos[model->jnt_qposadr[rear]] = 2.0;     // γr = 2.0
  mj_kinematics(model.get(), data.get());
  const auto axle = [&](const char* name) {
    return data->xpos + 3 * require_id(*model, mjOBJ_BODY, name);
  };
  const mjtNum* center = data->xpos + 3 * require_id(*model, mjOBJ_BODY, kCenterUnitName);
  const double a = 0.145, b = 0.413;
  const auto distance = [&](const mjtNum* p) {
    return std::hypot(p[0] - center[0], p[2] - center[2]);
  };
  EXPECT_NEAR(distance(axle("front_axle")), std::sqrt(a * a + b * b - 2 * a * b * std::cos(2.55)),
              1e-9);
  EXPECT_NEAR(distance(axle("rear_axle")), std::sqrt(a * a + b * b - 2 * a * b * std::cos(2.0)),
              1e-9);
  EXPECT_GT(axle("front_axle")[0], 0.0);
  EXPECT_LT(axle("rear_axle")[0], 0.0);
}

TEST(RoverMjcf, RejectsAnUnbuildableTimestep) {
  EXPECT_THROW(rover_mjcf(Params{}, TerrainSpec{}, 0.0), std::invalid_argument);
  EXPECT_THROW(rover_mjcf(Params{}, TerrainSpec{}, 0.1), std::invalid_argument);
}

TEST(RoverMjcf, NamesFollowTheMotorLayout) {
  EXPECT_EQ(wheel_name(kFrontLeft), "wheel_FL");
  EXPECT_EQ(motor_actuator_name(kRearJoint), "motor_AR");
  EXPECT_EQ(joint_hinge_name(kFrontJoint), "joint_AF");
  EXPECT_EQ(shaft_hinge_name(kRearJoint), "shaft_AR");
  EXPECT_EQ(joint_lock_name(kFrontJoint), "lock_AF");
  EXPECT_EQ(joint_coupling_name(kRearJoint), "couple_AR");
  EXPECT_EQ(wheel_block_name(kCenterRight), "block_CR");
}

}  // namespace
}  // namespace marsokhod::sim
