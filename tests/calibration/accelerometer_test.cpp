// Procedure 3.3 on the simulated bench: the six stand placements give the simulator's true ±g
// table (drawn per unit ±2 counts around the configured one), and the fit refuses readings that
// are not at rest, too few, or a placement that was not the one asked for.
#include "calibration/accelerometer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "calibration/procedures.hpp"
#include "calibration_test_support.hpp"
#include "config/calibration.hpp"
#include "sim/rover/simulated_rover.hpp"

namespace marsokhod::calibration {
namespace {

using namespace testing;

// The mean of ≥ 190 readings with 0.7 counts of noise before rounding is good to ≈ 0.1 count;
// the truth is drawn ±2 counts from the configured table, so 0.5 count separates them.
constexpr double kToleranceCounts = 0.5;
// Seed 5's unit differs from the configured table by more than the tolerance in every entry
// (asserted below), so returning the configured table fails.
constexpr std::uint64_t kSeed = 5;

// Synthetic placements of a sensor with the given table, noise and count per placement.
std::vector<AccelerometerPlacement> synthetic(const SensorParams& table, double noise_counts,
                                              std::size_t count) {
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, noise_counts);
  std::vector<AccelerometerPlacement> placements;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    for (bool up : {true, false}) {
      AccelerometerPlacement p{axis, up, {}};
      for (std::size_t k = 0; k < count; ++k) {
        std::array<double, 3> r{};
        for (std::size_t i = 0; i < 3; ++i) {
          const auto& t = table.accelerometer[i];
          const double level = 0.5 * (t.plus_g_counts + t.minus_g_counts);
          r[i] = i != axis ? level : (up ? t.plus_g_counts : t.minus_g_counts);
          r[i] = std::round(r[i] + noise(random));
        }
        p.readings_counts.push_back(r);
      }
      placements.push_back(std::move(p));
    }
  }
  return placements;
}

TEST(AccelerometerCalibration, RecoversTheSimulatorsTrueTable) {
  const Params params = config();
  SimBench bench(params, sim_bench_options(kSeed));
  const ProcedureResult result = run_procedure(bench, "accelerometer");
  ASSERT_TRUE(result.accepted()) << first(result.problems);
  const auto& truth = bench.rover().sim_truth().sensors.accelerometer;
  const Params fitted = config::apply_calibration_values(kConfigFile, result.values);
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const auto& got = fitted.sensors.accelerometer[axis];
    const auto& nominal = params.sensors.accelerometer[axis];
    EXPECT_NEAR(got.minus_g_counts, truth[axis].minus_g_counts, kToleranceCounts) << axis;
    EXPECT_NEAR(got.plus_g_counts, truth[axis].plus_g_counts, kToleranceCounts) << axis;
    // The configured table is not what the unit reads.
    EXPECT_GT(std::abs(nominal.minus_g_counts - truth[axis].minus_g_counts), kToleranceCounts);
    EXPECT_GT(std::abs(nominal.plus_g_counts - truth[axis].plus_g_counts), kToleranceCounts);
  }
  EXPECT_LT(result.quality.at("max_rest_sd_counts"), 1.0);
  EXPECT_LT(result.quality.at("max_cross_axis_fraction"), 0.02);
  ASSERT_EQ(result.recordings.size(), 1u);
  EXPECT_FALSE(result.recordings[0].gnuplot.empty());
}

TEST(AccelerometerCalibration, TheFitOfCleanDataIsTheTable) {
  SensorParams table;
  table.accelerometer = {{{140.0, 410.0}, {125.0, 380.0}, {70.0, 380.0}}};
  const ProcedureResult result = fit_accelerometer(synthetic(table, 0.7, 200), SensorParams{});
  ASSERT_TRUE(result.accepted()) << first(result.problems);
  const Params fitted = config::apply_calibration_values(kConfigFile, result.values);
  for (std::size_t axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(fitted.sensors.accelerometer[axis].minus_g_counts,
                table.accelerometer[axis].minus_g_counts, 0.2);
    EXPECT_NEAR(fitted.sensors.accelerometer[axis].plus_g_counts,
                table.accelerometer[axis].plus_g_counts, 0.2);
  }
}

TEST(AccelerometerCalibration, RefusesReadingsNotAtRest) {
  const ProcedureResult result = fit_accelerometer(synthetic(SensorParams{}, 6.0, 200),
                                                   SensorParams{});
  EXPECT_FALSE(result.accepted());
  EXPECT_TRUE(mentions(result.problems, "not at rest")) << first(result.problems);
  EXPECT_TRUE(result.values.empty());
}

TEST(AccelerometerCalibration, RefusesTooFewReadings) {
  const ProcedureResult result = fit_accelerometer(synthetic(SensorParams{}, 0.7, 10),
                                                   SensorParams{});
  EXPECT_FALSE(result.accepted());
  EXPECT_TRUE(mentions(result.problems, "only 10 readings")) << first(result.problems);
}

TEST(AccelerometerCalibration, RefusesAPlacementThatWasNotTheOneAskedFor) {
  // "x1 down" taken with x1 up again: no span on acc1.
  std::vector<AccelerometerPlacement> placements = synthetic(SensorParams{}, 0.7, 200);
  placements[1].readings_counts = placements[0].readings_counts;
  const ProcedureResult result = fit_accelerometer(placements, SensorParams{});
  EXPECT_FALSE(result.accepted());
  EXPECT_TRUE(mentions(result.problems, "acc1: up and down differ by")) << first(result.problems);
  // A missing placement is named.
  placements = synthetic(SensorParams{}, 0.7, 200);
  placements.pop_back();
  const ProcedureResult missing = fit_accelerometer(placements, SensorParams{});
  EXPECT_TRUE(mentions(missing.problems, "x3 down is missing")) << first(missing.problems);
}

TEST(AccelerometerCalibration, IsInTheProcedureTable) {
  const ProcedureInfo* info = find_procedure("accelerometer");
  ASSERT_NE(info, nullptr);
  EXPECT_EQ(info->reference, "Procedure 3.3");
}

}  // namespace
}  // namespace marsokhod::calibration
