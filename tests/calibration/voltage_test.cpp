// Procedure 3.5 against the simulator: the drawn unit's divider and ADC differ from the
// configuration's U = 0.06768·vcc − 41.0823; the procedure finds the unit's own line.
#include "calibration/voltage.hpp"

#include <gtest/gtest.h>

#include "calibration/procedures.hpp"
#include "calibration_test_support.hpp"
#include "config/calibration.hpp"
#include "sim/rover/simulated_rover.hpp"

namespace marsokhod::calibration {
namespace {

using namespace testing;

TEST(VoltageProcedure, RecoversTheUnitsSupplyConversion) {
  const Params params = config();
  SimBench bench(params, sim_bench_options(11));
  const ProcedureResult result = run_procedure(bench, "voltage");
  ASSERT_TRUE(result.accepted()) << result.problems.front();
  const LinearConversion truth = bench.rover().sim_truth().sensors.supply;
  const Params fitted = config::apply_calibration_values(kConfigFile, result.values);
  // Over battery operation's range, 20–27 V: vcc from 900 down to 890… wherever the unit reads.
  double worst_fitted = 0.0;
  double worst_nominal = 0.0;
  for (double volts = 20.0; volts <= 27.0; volts += 0.5) {
    const double vcc = (volts - truth.offset) / truth.gain;  // the unit's true reading
    worst_fitted = std::max(worst_fitted, std::abs(fitted.sensors.supply(vcc) - volts));
    worst_nominal = std::max(worst_nominal, std::abs(params.sensors.supply(vcc) - volts));
  }
  // Quantisation (±34 mV, thesis) averaged over 128 readings a voltage, 8 voltages: 15 mV.
  EXPECT_LT(worst_fitted, 0.015);
  EXPECT_GT(worst_nominal, 0.05) << "the drawn unit must differ from the configuration";
  EXPECT_NEAR(fitted.sensors.supply.gain, truth.gain, 0.001 * truth.gain);
  EXPECT_LT(result.quality.at("max_residual_v"), 0.05);
  // The reading's error the tether's current bound allows for: the worst residual and a count,
  // more than the fitted line is off the unit's and a tenth of the uncalibrated 1.2 V.
  EXPECT_NEAR(result.values["power"]["supply_reading_error_v"].value_or(0.0),
              result.quality.at("max_residual_v") + fitted.sensors.supply.gain, 1e-12);
  EXPECT_GT(fitted.power.current.supply_reading_error_v, worst_fitted);
  EXPECT_LT(fitted.power.current.supply_reading_error_v, 0.12);
  EXPECT_EQ(result.quality.at("points"), 8.0);
  // Back at the nominal voltage for whatever comes next.
  EXPECT_NEAR(bench.measure_supply_v(), 24.0, 0.2);
}

std::vector<VoltagePoint> clean_points() {
  std::vector<VoltagePoint> points;
  for (double volts = 27.0; volts >= 20.0; volts -= 1.0) {
    points.push_back({volts, (volts + 41.0823) / 0.06768, 0.4, 128});
  }
  return points;
}

TEST(VoltageFit, AcceptsCleanPointsAndRefusesPoorOnes) {
  const ProcedureResult clean = fit_voltage(clean_points());
  ASSERT_TRUE(clean.accepted());
  EXPECT_NEAR(clean.values["sensors"]["supply_v_per_count"].value_or(0.0), 0.06768, 1e-9);

  std::vector<VoltagePoint> noisy = clean_points();
  noisy[3].vcc_sd_counts = 6.0;  // a supply that wanders
  EXPECT_TRUE(mentions(fit_voltage(noisy).problems, "wanders"));

  std::vector<VoltagePoint> off = clean_points();
  off[2].measured_v += 0.3;  // a misread multimeter
  EXPECT_TRUE(mentions(fit_voltage(off).problems, "off the line"));

  std::vector<VoltagePoint> few = clean_points();
  few.resize(3);
  EXPECT_TRUE(mentions(fit_voltage(few).problems, "at least 4"));

  std::vector<VoltagePoint> short_hold = clean_points();
  short_hold[0].samples = 5;
  EXPECT_TRUE(mentions(fit_voltage(short_hold).problems, "only 5 readings"));

  std::vector<VoltagePoint> narrow;
  for (double volts : {24.0, 24.5, 25.0, 25.5}) {
    narrow.push_back({volts, (volts + 41.0823) / 0.06768, 0.4, 128});
  }
  EXPECT_TRUE(mentions(fit_voltage(narrow).problems, "span only"));
}

TEST(VoltageProcedure, IsInTheTable) {
  const ProcedureInfo* info = find_procedure("voltage");
  ASSERT_NE(info, nullptr);
  EXPECT_EQ(info->reference, "Procedure 3.5");
  EXPECT_TRUE(info->needs_bench);
  EXPECT_EQ(find_procedure("voltmeter"), nullptr);
}

}  // namespace
}  // namespace marsokhod::calibration
