#include "core/tracking/reference_voltage.hpp"

#include <cmath>
#include <limits>

#include "tracking_test_support.hpp"

namespace marsokhod::tracking {
namespace {

using testing::invalid_argument_message;

TEST(ReferenceVoltage, StartsAtTheFirstReading) {
  // Ū⁰ = U⁰ = 24.5, so Ū¹ = max(24.5, 24.5) = 24.5 whatever the duty cycles.
  ReferenceVoltage reference(0.99);
  EXPECT_FALSE(reference.started());
  EXPECT_DOUBLE_EQ(reference.update(24.5, false), 24.5);
  EXPECT_TRUE(reference.started());
}

TEST(ReferenceVoltage, HoldsWhileDrivingAndRisesWithU) {
  ReferenceVoltage reference(0.99);
  reference.update(24.5, true);
  // Driving under load U drops to 23.0: Ū = max(23.0, 24.5) = 24.5, held.
  for (int k = 0; k < 50; ++k) {
    EXPECT_DOUBLE_EQ(reference.update(23.0, false), 24.5);
  }
  // U above Ū lifts it at once: Ū = max(25.0, 24.5) = 25.0.
  EXPECT_DOUBLE_EQ(reference.update(25.0, false), 25.0);
}

TEST(ReferenceVoltage, DecaysTowardUOnlyWhileAllDutyCyclesAreZero) {
  // From Ū = 25 with U = 24 and all d_i = 0: Ū^n = 24 + 1·0.99^n, e.g. Ū¹ = 24.99,
  // Ū¹⁰⁰ = 24.366.
  ReferenceVoltage reference(0.99);
  reference.update(25.0, true);
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

TEST(ReferenceVoltage, NeverBelowU) {
  // A discharging battery with load steps: U^k ≤ Ū^(k+1) every cycle, whatever the duty flag.
  ReferenceVoltage reference(0.95);
  for (int k = 0; k < 2000; ++k) {
    const double battery_v = 26.5 - 0.002 * k;
    const bool all_duty_zero = (k / 37) % 3 == 0;
    const double load_drop_v = all_duty_zero ? 0.0 : 0.8 + 0.5 * std::sin(0.1 * k);
    const double supply_v = battery_v - load_drop_v + 0.03 * std::sin(1.7 * k);  // ±34 mV noise
    const double reference_v = reference.update(supply_v, all_duty_zero);
    ASSERT_LE(supply_v, reference_v) << "cycle " << k;
  }
}

TEST(ReferenceVoltage, RejectsInvalidInput) {
  EXPECT_THAT(invalid_argument_message([] { ReferenceVoltage reference(-0.1); }),
              ::testing::HasSubstr("filters.reference_voltage_lambda"));
  ReferenceVoltage reference(0.99);
  reference.update(24.0, true);
  EXPECT_THROW(reference.update(std::numeric_limits<double>::quiet_NaN(), true),
               std::invalid_argument);
  EXPECT_DOUBLE_EQ(reference.reference_v(), 24.0);
}

}  // namespace
}  // namespace marsokhod::tracking
