// Procedures 4.3 and 4.1 on the simulated bench: the driver's own start-up step initialises the
// joints (shafts at the negative end of their gaps), and reversing the joint motors at d = ±0.1
// on the ground measures the gaps, which the simulator draws per unit 6–15 % away from the
// configured 3° and 14° (sim_truth.hpp).
#include "calibration/joints.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "calibration/procedures.hpp"
#include "calibration_test_support.hpp"
#include "config/calibration.hpp"
#include "sim/rover/simulated_rover.hpp"

namespace marsokhod::calibration {
namespace {

using namespace testing;

constexpr std::uint64_t kSeed = 4;

// The travel between the shaft's resting places is the gap plus how far the gap's soft ends give
// under the stalled motor's torque at d = 0.1 (both ends, well under a milliradian), and the
// encoder's 55 µrad: 3 % of the gap plus 1 mrad holds it, while the truth lies at least 6 % from
// the configured value.
double tolerance_rad(double truth_rad) { return 0.03 * truth_rad + 0.001; }

std::array<std::vector<JointHold>, 2> holds_of(const std::vector<double>& front,
                                               const std::vector<double>& rear,
                                               double rest_speed_radps = 0.0) {
  std::array<std::vector<JointHold>, 2> holds;
  for (std::size_t k = 0; k < front.size(); ++k) {
    const double duty = k % 2 == 0 ? 0.1 : -0.1;
    holds[0].push_back({duty, front[k], rest_speed_radps});
    holds[1].push_back({duty, rear[k], rest_speed_radps});
  }
  return holds;
}

TEST(JointsCalibration, InitialisesTheJointsAndMeasuresTheTrueBacklash) {
  const Params params = config();
  SimBench bench(params, sim_bench_options(kSeed));
  const ProcedureResult result = run_procedure(bench, "joints");
  ASSERT_TRUE(result.accepted()) << first(result.problems);
  const sim::SimTruth& truth = bench.rover().sim_truth();
  const Params fitted = config::apply_calibration_values(kConfigFile, result.values);
  for (std::size_t motor : {kFrontJoint, kRearJoint}) {
    const double true_b = truth.motors[motor].backlash_rad;
    EXPECT_NEAR(fitted.motors.backlash_rad[motor], true_b, tolerance_rad(true_b)) << motor;
    EXPECT_GT(std::abs(params.motors.backlash_rad[motor] - true_b), tolerance_rad(true_b))
        << "the configured backlash of motor " << motor << " would pass";
  }
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    EXPECT_EQ(fitted.motors.backlash_rad[wheel], params.motors.backlash_rad[wheel]);
  }
  // Procedure 4.3's state at the end: each shaft rests at the negative end of its gap, so that
  // with the rover strapped down again a negative duty cycle cannot move it at all.
  BenchSetup strapped;
  strapped.strapped_down = true;
  bench.arrange(strapped);
  const MotorVector before = bench.last().position_rad;
  MotorVector negative{};
  negative[kFrontJoint] = negative[kRearJoint] = -0.1;
  bench.hold(negative, 1.5);
  for (std::size_t motor : {kFrontJoint, kRearJoint}) {
    EXPECT_NEAR(bench.last().position_rad[motor], before[motor], 0.002) << motor;
  }
  EXPECT_LE(result.quality.at("initialisation_s"), 3.5);
  EXPECT_GE(result.quality.at("front_reversals"), 5.0);
  ASSERT_EQ(result.recordings.size(), 1u);
  EXPECT_FALSE(result.recordings[0].rows.empty());
}

TEST(JointsCalibration, TheFitIsTheMeanTravel) {
  const ProcedureResult result = fit_joints(
      holds_of({0.0, 0.05, 0.001, 0.052, 0.0}, {0.0, 0.25, 0.002, 0.254, 0.0}), {},
      MotorParams{});
  ASSERT_TRUE(result.accepted()) << first(result.problems);
  EXPECT_NEAR(result.quality.at("front_backlash_rad"), (0.05 + 0.049 + 0.051 + 0.052) / 4, 1e-12);
  EXPECT_NEAR(result.quality.at("rear_backlash_rad"), (0.25 + 0.248 + 0.252 + 0.254) / 4, 1e-12);
}

TEST(JointsCalibration, RefusesAJointThatMoved) {
  const ProcedureResult result =
      fit_joints(holds_of({0.0, 0.05, 0.0, 0.05}, {0.0, 0.25, 0.0, 0.25}, 0.05), {}, MotorParams{});
  EXPECT_FALSE(result.accepted());
  EXPECT_TRUE(mentions(result.problems, "the joint moved")) << first(result.problems);
  EXPECT_TRUE(result.values.empty());
}

TEST(JointsCalibration, RefusesReversalsThatDisagree) {
  const ProcedureResult result = fit_joints(
      holds_of({0.0, 0.05, 0.0, 0.09, 0.0}, {0.0, 0.25, 0.0, 0.25, 0.0}), {}, MotorParams{});
  EXPECT_FALSE(result.accepted());
  EXPECT_TRUE(mentions(result.problems, "front joint: the reversals disagree"))
      << first(result.problems);
}

TEST(JointsCalibration, RefusesTooFewReversals) {
  const ProcedureResult result =
      fit_joints(holds_of({0.0, 0.05}, {0.0, 0.25}), {}, MotorParams{});
  EXPECT_FALSE(result.accepted());
  EXPECT_TRUE(mentions(result.problems, "1 reversals measured")) << first(result.problems);
}

TEST(JointsCalibration, IsInTheProcedureTable) {
  const ProcedureInfo* info = find_procedure("joints");
  ASSERT_NE(info, nullptr);
  // The registry holds the one reference, the calibration file's (Procedure 4.1 measures b).
  EXPECT_TRUE(info->reference.starts_with("Procedure 4.3")) << info->reference;
}

}  // namespace
}  // namespace marsokhod::calibration
