#include "sim/soil/wheel_stress.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>
#include <numbers>

#include "../../support/invalid_argument.hpp"
#include "wong_reece_reference.hpp"

namespace marsokhod::sim::soil {
namespace {

// A Marsokhod wheel's share of the 82 kg rover (six wheels, chapter 3.1's masses), in N.
constexpr double kWheelLoadN = 82.0 * 9.81 / 6.0;

reference::Soil reference_soil(const SoilParams& soil) {
  return {soil.sinkage_exponent,    soil.slip_sinkage_exponent,
          soil.cohesive_modulus,    soil.frictional_modulus,
          soil.cohesion_pa,         soil.friction_angle_rad,
          soil.shear_modulus_m,     soil.soil_metal_friction_angle_rad,
          soil.max_stress_angle_c1, soil.max_stress_angle_c2};
}

reference::Wheel reference_wheel(const WheelGeometry& wheel) {
  return {wheel.rim_radius_m,
          wheel.shear_radius_m(),
          wheel.width_m,
          wheel.blade_inclination_rad,
          static_cast<int>(wheel.handedness),
          wheel.bladed};
}

// Bekker's towed rigid wheel: the normal stress is the plate's pressure k z^n along the front arc
// and nothing else (θm = θ2 = 0, a frictionless soil so no shear). His closed form
//   z0 = [3W / ((3 − n)(k_c + b k_φ) √D)]^(2/(2n+1))
// takes the arc for a parabola and ∫(1 − u²)^n du for (3 − n)/3 (exact for n = 1); at this
// sinkage (z/r ≤ 0.27) both approximations together stay within 1.5 %.
TEST(WheelStress, StaticSinkageMatchesBekkersClosedForm) {
  SoilParams soil = dry_sand();
  soil.max_stress_angle_c1 = 0.0;
  soil.max_stress_angle_c2 = 0.0;
  soil.cohesion_pa = 0.0;
  soil.friction_angle_rad = 0.0;
  WheelGeometry wheel;
  wheel.arc_samples = 256;
  const double n = soil.sinkage_exponent, b = wheel.width_m;
  for (double load : {0.5 * kWheelLoadN, kWheelLoadN, 2.0 * kWheelLoadN}) {
    const double bekker =
        std::pow(3.0 * load /
                     ((3.0 - n) * (soil.cohesive_modulus + b * soil.frictional_modulus) *
                      std::sqrt(2.0 * wheel.rim_radius_m)),
                 2.0 / (2.0 * n + 1.0));
    const double sinkage = equilibrium_sinkage_m(soil, wheel, load, 0.0);
    EXPECT_NEAR(sinkage / bekker, 1.0, 0.015) << "load " << load << " N";
  }
  // n = 1 removes the (3 − n)/3 approximation: only the parabola is left, 1 % at a light load.
  soil.sinkage_exponent = 1.0;
  const double load = 0.5 * kWheelLoadN;
  const double bekker = std::pow(3.0 * load /
                                     (2.0 * (soil.cohesive_modulus + b * soil.frictional_modulus) *
                                      std::sqrt(2.0 * wheel.rim_radius_m)),
                                 2.0 / 3.0);
  EXPECT_NEAR(equilibrium_sinkage_m(soil, wheel, load, 0.0) / bekker, 1.0, 0.01);
}

// Drawbar pull over weight and sinkage against slip, −0.2 … 0.8, for the default sand and the
// Marsokhod wheel, against the separate reference: the library's 24-sample midpoint rule differs
// from the reference's 4000-interval Simpson by less than 0.5 % of the sinkage and 0.003 in DP/W.
void expect_matches_reference(const SoilParams& soil, const WheelGeometry& wheel) {
  for (int step = 0; step <= 10; ++step) {
    const double slip = -0.2 + 0.1 * step;
    const reference::Result expected =
        reference::at_load(reference_soil(soil), reference_wheel(wheel), kWheelLoadN, slip);
    const double sinkage = equilibrium_sinkage_m(soil, wheel, kWheelLoadN, slip);
    const PlanarForces forces = steady_wheel_forces(soil, wheel, sinkage, slip);
    EXPECT_NEAR(sinkage / expected.sinkage_m, 1.0, 0.005) << "slip " << slip;
    EXPECT_NEAR(forces.drawbar_pull_n / kWheelLoadN, expected.drawbar_pull_n / expected.weight_n,
                0.003)
        << "slip " << slip;
  }
}

TEST(WheelStress, DrawbarPullAndSinkageAgainstSlipMatchReferenceSmoothRim) {
  WheelGeometry wheel;
  wheel.bladed = false;
  expect_matches_reference(dry_sand(), wheel);
}

TEST(WheelStress, DrawbarPullAndSinkageAgainstSlipMatchReferenceBladed) {
  expect_matches_reference(dry_sand(), WheelGeometry{});
  SoilParams sinking = dry_sand();
  sinking.slip_sinkage_exponent = 0.3;  // n grows with slip: the wheel sinks deeper as it spins
  expect_matches_reference(sinking, WheelGeometry{});
  expect_matches_reference(lunar_soil(), WheelGeometry{});
}

// The shape Wong–Reece predicts: a towed wheel (s < 0) is pulled back, the pull rises with slip
// and saturates; with n1 > 0 the sinkage grows with slip (and the pull then falls off again at high
// slip, as the wheel digs in).
TEST(WheelStress, DrawbarPullRisesWithSlipAndSlipSinkageDeepens) {
  const WheelGeometry wheel;
  SoilParams soil = dry_sand();
  double previous_pull = -1e9;
  for (double slip : {0.0, 0.2, 0.4, 0.6, 0.8, 1.0}) {
    const double sinkage = equilibrium_sinkage_m(soil, wheel, kWheelLoadN, slip);
    const double pull = steady_wheel_forces(soil, wheel, sinkage, slip).drawbar_pull_n;
    EXPECT_GT(pull, previous_pull) << "slip " << slip;
    previous_pull = pull;
  }
  const double towed = equilibrium_sinkage_m(soil, wheel, kWheelLoadN, -0.2);
  EXPECT_LT(steady_wheel_forces(soil, wheel, towed, -0.2).drawbar_pull_n, 0.0);
  soil.slip_sinkage_exponent = 0.3;
  double previous_sinkage = 0.0;
  for (double slip : {0.0, 0.2, 0.4, 0.6, 0.8, 1.0}) {
    const double sinkage = equilibrium_sinkage_m(soil, wheel, kWheelLoadN, slip);
    EXPECT_GT(sinkage, previous_sinkage) << "slip " << slip;
    previous_sinkage = sinkage;
  }
}

// Inclined blades turn part of the longitudinal shear sideways; blades across the axle (i = 0)
// or a smooth rim do not.
TEST(WheelStress, InclinedBladesPushSidewaysAtSlip) {
  const SoilParams soil = dry_sand();
  WheelGeometry right;
  WheelGeometry left;
  left.handedness = BladeHandedness::kLeft;
  WheelGeometry straight;
  straight.blade_inclination_rad = 0.0;
  WheelGeometry smooth;
  smooth.bladed = false;
  const double sinkage = equilibrium_sinkage_m(soil, right, kWheelLoadN, 0.5);
  const double lateral_right = steady_wheel_forces(soil, right, sinkage, 0.5).lateral_n;
  EXPECT_LT(lateral_right, -0.01 * kWheelLoadN);  // −2.3 N: the across-blade shear's share
  EXPECT_DOUBLE_EQ(steady_wheel_forces(soil, left, sinkage, 0.5).lateral_n, -lateral_right);
  EXPECT_NEAR(steady_wheel_forces(soil, straight, sinkage, 0.5).lateral_n, 0.0, 1e-9);
  EXPECT_NEAR(steady_wheel_forces(soil, smooth, sinkage, 0.5).lateral_n, 0.0, 1e-9);
}

TEST(WheelStress, ContactArcAndStressLaws) {
  const SoilParams soil = dry_sand();
  const ContactArc arc = contact_arc(soil, 0.115, 0.02, 0.5);
  EXPECT_NEAR(arc.entry_rad, std::acos(1.0 - 0.02 / 0.115), 1e-12);
  EXPECT_NEAR(arc.max_stress_rad, (0.4 + 0.15 * 0.5) * arc.entry_rad, 1e-12);
  EXPECT_DOUBLE_EQ(normal_stress_pa(soil, arc, 0.115, 0.15, arc.entry_rad), 0.0);
  EXPECT_DOUBLE_EQ(normal_stress_pa(soil, arc, 0.115, 0.15, arc.entry_rad + 0.1), 0.0);
  // At θm the stress is the plate's at the full sinkage under that point.
  const double at_max = normal_stress_pa(soil, arc, 0.115, 0.15, arc.max_stress_rad);
  const double depth = 0.115 * (std::cos(arc.max_stress_rad) - std::cos(arc.entry_rad));
  EXPECT_NEAR(at_max, (990.0 / 0.15 + 1528430.0) * std::pow(depth, 1.1), 1e-6 * at_max);
  // Janosi–Hanamoto: 63 % of the strength at j = K, odd in j.
  const double strength = 1040.0 + 1e4 * std::tan(soil.friction_angle_rad);
  EXPECT_NEAR(soil_shear_pa(soil, 1e4, soil.shear_modulus_m), strength * (1.0 - std::exp(-1.0)),
              1e-9);
  EXPECT_DOUBLE_EQ(soil_shear_pa(soil, 1e4, -0.01), -soil_shear_pa(soil, 1e4, 0.01));
  EXPECT_DOUBLE_EQ(regularised_slip(0.0, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(regularised_slip(1.0, 0.8), 0.2 / 1.0);
  EXPECT_DOUBLE_EQ(regularised_slip(0.8, 1.0), -0.2);
}

// The arc's normal stresses in one pass, two exponentials at a time, are those of one sample at a
// time, bit for bit: over an odd count, at n = 1, and past the arc where σ = 0.
TEST(WheelStress, NormalStressesInPairsAreTheSingleOnes) {
  const SoilParams soil = dry_sand();
  for (const double slip : {0.0, 0.4}) {
    const ContactArc arc = contact_arc(soil, 0.115, 0.03, slip);
    for (const double n : {arc.sinkage_exponent, 1.0}) {
      ContactArc with_n = arc;
      with_n.sinkage_exponent = n;
      std::vector<double> cosines;
      for (int k = 0; k < 25; ++k) cosines.push_back(std::cos(arc.entry_rad * (1.1 - 0.09 * k)));
      std::vector<double> stresses = cosines;
      normal_stresses_from_cos_pa(5e5, with_n, 0.115, stresses.data(),
                                  static_cast<int>(stresses.size()));
      for (std::size_t k = 0; k < cosines.size(); ++k) {
        EXPECT_EQ(stresses[k], normal_stress_from_cos_pa(5e5, with_n, 0.115, cosines[k])) << k;
      }
      EXPECT_EQ(stresses[0], 0.0);  // θ = 1.1 θ1, ahead of the arc
      EXPECT_GT(stresses[5], 0.0);
    }
  }
}

TEST(WheelStress, SidewallIsRankinesPassivePressureOnTheSegment) {
  SoilParams soil = dry_sand();
  EXPECT_DOUBLE_EQ(sidewall_resistance_n(soil, 0.115, 0.0), 0.0);
  // Cohesion only: 2c√N_φ times the segment's area.
  soil.bulk_density_kgpm3 = 1.0;
  soil.gravity_mps2 = 0.0;
  const double r = 0.115, z = 0.03,
               passive = std::pow(std::tan(std::numbers::pi / 4 + soil.friction_angle_rad / 2), 2);
  const double half_angle = std::acos((r - z) / r);
  const double segment = r * r * (half_angle - std::sin(half_angle) * std::cos(half_angle));
  EXPECT_NEAR(sidewall_resistance_n(soil, r, z),
              2.0 * soil.cohesion_pa * std::sqrt(passive) * segment,
              1e-12 * 2.0 * soil.cohesion_pa * std::sqrt(passive) * segment);
}

TEST(WheelStress, SidewallsWeightTermIsTheDepthIntegratedOverTheSegment) {
  // Friction only: ρ g N_φ ∫ depth · chord, against a fine midpoint sum over the depth.
  SoilParams soil = dry_sand();
  soil.cohesion_pa = 0.0;
  const double passive = passive_earth_coefficient(soil);
  for (const double z : {1e-5, 1.1e-4, 1.2e-4, 0.005, 0.03, 0.115}) {  // both sides of 1e-3·r
    const double r = 0.115;
    constexpr int kSamples = 200000;
    double integral = 0.0;
    for (int k = 0; k < kSamples; ++k) {
      const double depth = (k + 0.5) * z / kSamples;
      const double from_center = r - z + depth;
      integral += depth * 2.0 * std::sqrt(r * r - from_center * from_center) * z / kSamples;
    }
    const double expected = soil.bulk_density_kgpm3 * soil.gravity_mps2 * passive * integral;
    const double tolerance = z < 1e-3 * r ? z / r : 1e-6;  // the series' relative error: z/r
    EXPECT_NEAR(sidewall_resistance_n(soil, r, z), expected, tolerance * expected) << z;
  }
  // Never negative, however little the wheel sinks (the closed form's differences cancel there).
  for (double z = 1e-12; z < 0.01; z *= 1.7) {
    EXPECT_GE(sidewall_resistance_n(soil, 0.115, z), 0.0) << z;
    EXPECT_GE(sidewall_resistance_n(dry_sand(), 0.115, z), 0.0) << z;
  }
}

TEST(WheelStress, RejectsALoadTheSoilCannotCarry) {
  test_support::expect_invalid_argument(
      [] { equilibrium_sinkage_m(dry_sand(), WheelGeometry{}, 1e6, 0.0); },
      {"cannot carry", "sinks to its axle"});
  test_support::expect_invalid_argument(
      [] { equilibrium_sinkage_m(dry_sand(), WheelGeometry{}, -1.0, 0.0); }, {"load", ">= 0 N"});
}

}  // namespace
}  // namespace marsokhod::sim::soil
