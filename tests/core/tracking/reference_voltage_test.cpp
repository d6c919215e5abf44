#include "core/tracking/reference_voltage.hpp"

#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "tracking_test_support.hpp"

namespace marsokhod::tracking {
namespace {

using testing::invalid_argument_message;

// Ū after the 16 readings of the warm-up, all at supply_v.
ReferenceVoltage warmed_up(double lambda, double supply_v) {
  ReferenceVoltage reference(lambda);
  for (std::size_t k = 0; k < kSupplyAveragingReadings; ++k) reference.update(supply_v, true);
  return reference;
}

TEST(ReferenceVoltage, StartsAtTheMeanOfTheFirstReadings) {
  // Ū¹ = U⁰ = 24.5; then the mean of the readings so far, whatever the duty cycles (the joints
  // move during start-up): Ū² = (24.5 + 24.3)/2 = 24.4, Ū³ = (24.5 + 24.3 + 24.4)/3 = 24.4.
  ReferenceVoltage reference(0.99);
  EXPECT_FALSE(reference.started());
  EXPECT_DOUBLE_EQ(reference.update(24.5, false), 24.5);
  EXPECT_TRUE(reference.started());
  EXPECT_DOUBLE_EQ(reference.update(24.3, false), 24.4);
  EXPECT_NEAR(reference.update(24.4, true), 24.4, 1e-12);
  // A first reading a count high does not stick: 24.568 then fifteen readings of 24.5 give
  // Ū = 24.50425 after the warm-up, and the motors running from then on hold that.
  ReferenceVoltage noisy(0.99);
  noisy.update(24.568, false);
  for (int k = 1; k < 16; ++k) noisy.update(24.5, false);
  EXPECT_NEAR(noisy.reference_v(), 24.50425, 1e-12);
  EXPECT_NEAR(noisy.update(23.0, false), 24.50425, 1e-12);
}

TEST(ReferenceVoltage, HoldsWhileDrivingAndRisesWithU) {
  ReferenceVoltage reference = warmed_up(0.99, 24.5);
  // Driving under load U drops to 23.0: Ū = max(Ũ ≤ 24.5, 24.5) = 24.5, held.
  for (int k = 0; k < 50; ++k) {
    EXPECT_DOUBLE_EQ(reference.update(23.0, false), 24.5);
  }
  // U rising above Ū lifts it once the mean of the last 16 readings does: after n readings of
  // 25.0, Ũ = (23·(16 − n) + 25·n)/16, which reaches 24.5 at n = 12 and is 25.0 at n = 16.
  for (int n = 1; n <= 12; ++n) {
    EXPECT_DOUBLE_EQ(reference.update(25.0, false), 24.5) << "reading " << n;
  }
  EXPECT_DOUBLE_EQ(reference.update(25.0, false), 24.625);
  for (int n = 14; n <= 16; ++n) reference.update(25.0, false);
  EXPECT_DOUBLE_EQ(reference.reference_v(), 25.0);
}

TEST(ReferenceVoltage, DecaysTowardUOnlyWhileAllDutyCyclesAreZero) {
  // From Ū = 25 with U = 24 and all d_i = 0: Ū^n = 24 + 1·0.99^n (Ũ, a mean of 25s and 24s,
  // stays below), e.g. Ū¹ = 24.99, Ū¹⁰⁰ = 24.366.
  ReferenceVoltage reference = warmed_up(0.99, 25.0);
  EXPECT_NEAR(reference.update(24.0, true), 24.99, 1e-12);
  for (int n = 2; n <= 100; ++n) {
    reference.update(24.0, true);
  }
  EXPECT_NEAR(reference.reference_v(), 24.0 + std::pow(0.99, 100), 1e-9);
  EXPECT_NEAR(reference.reference_v(), 24.366, 1e-3);
  // A duty cycle ≠ 0 stops the decay.
  const double held_v = reference.reference_v();
  EXPECT_DOUBLE_EQ(reference.update(24.0, false), held_v);
}

TEST(ReferenceVoltage, NoisyReadingsDoNotRatchetUp) {
  // A battery at rest between two ADC counts (U = 0.06768·vcc − 41.0823: vcc 978 → 25.1088 V,
  // 979 → 25.1765 V) reads one or the other, and every 20th reading one count higher (25.2441 V).
  // The thesis' max(U^k, …) would take Ū to 25.2441 at the first high reading and hold it there
  // while the motors run; the mean of 16 readings keeps Ū within 0.02 V of the readings' mean.
  ReferenceVoltage reference(0.99);
  const double low_v = 0.06768 * 978 - 41.0823;
  const double high_v = 0.06768 * 980 - 41.0823;
  double sum_v = 0.0;
  const int readings = 400;
  for (int k = 0; k < readings; ++k) {
    const double u = k % 20 == 19 ? high_v : low_v + 0.06768 * ((k * 7) % 3 == 0 ? 1 : 0);
    sum_v += u;
    reference.update(u, k < 200);  // at rest for 200 cycles (3 s), then driving: Ū holds
  }
  const double mean_v = sum_v / readings;
  EXPECT_NEAR(reference.reference_v(), mean_v, 0.02);
  EXPECT_LT(reference.reference_v(), high_v - 0.04);
}

TEST(ReferenceVoltage, NeverBelowTheMeanOfTheLastReadings) {
  // A discharging battery with load steps: Ũ^k ≤ Ū^(k+1) every cycle, whatever the duty flag,
  // with Ũ the mean of the last 16 readings U^k.
  ReferenceVoltage reference(0.95);
  std::vector<double> readings;
  for (int k = 0; k < 2000; ++k) {
    const double battery_v = 26.5 - 0.002 * k;
    const bool all_duty_zero = (k / 37) % 3 == 0;
    const double load_drop_v = all_duty_zero ? 0.0 : 0.8 + 0.5 * std::sin(0.1 * k);
    const double supply_v = battery_v - load_drop_v + 0.03 * std::sin(1.7 * k);  // ±34 mV noise
    readings.push_back(supply_v);
    const std::size_t n = std::min<std::size_t>(readings.size(), kSupplyAveragingReadings);
    const double mean_v =
        std::accumulate(readings.end() - static_cast<std::ptrdiff_t>(n), readings.end(), 0.0) /
        static_cast<double>(n);
    const double reference_v = reference.update(supply_v, all_duty_zero);
    ASSERT_NEAR(reference.mean_supply_v(), mean_v, 1e-9) << "cycle " << k;
    ASSERT_LE(mean_v, reference_v + 1e-12) << "cycle " << k;
  }
}

TEST(ReferenceVoltage, RejectsInvalidInput) {
  EXPECT_THAT(invalid_argument_message([] { ReferenceVoltage reference(-0.1); }),
              ::testing::HasSubstr("filters.reference_voltage_lambda"));
  ReferenceVoltage reference = warmed_up(0.99, 24.0);
  EXPECT_THROW(reference.update(std::numeric_limits<double>::quiet_NaN(), true),
               std::invalid_argument);
  EXPECT_DOUBLE_EQ(reference.reference_v(), 24.0);
}

}  // namespace
}  // namespace marsokhod::tracking
