#include "sim/soil/wheel_soil.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "../../support/invalid_argument.hpp"
#include "wong_reece_reference.hpp"

namespace marsokhod::sim::soil {
namespace {

constexpr double kWheelLoadN = 82.0 * 9.81 / 6.0;
constexpr double kDt = 0.001;
const Vec3 kUp{0.0, 0.0, 1.0};

reference::Soil reference_soil(const SoilParams& soil) {
  return {soil.sinkage_exponent,    soil.slip_sinkage_exponent,
          soil.cohesive_modulus,    soil.frictional_modulus,
          soil.cohesion_pa,         soil.friction_angle_rad,
          soil.shear_modulus_m,     soil.soil_metal_friction_angle_rad,
          soil.max_stress_angle_c1, soil.max_stress_angle_c2,
          soil.unloading_stiffness_ratio};
}

// A single-wheel rig: the wheel at a fixed sinkage, turning at spin_radps and carried along x at
// the speed that gives slip s (Wong's definitions, wheel_stress.hpp), for duration_s.
WheelWrench run_rig(WheelSoilContact& contact, double sinkage_m, double spin_radps, double slip,
                    double duration_s) {
  const double rs = contact.wheel().shear_radius_m();
  const double speed =
      slip >= 0.0 ? rs * spin_radps * (1.0 - slip) : rs * spin_radps / (1.0 + slip);
  const std::vector<double> lanes(static_cast<std::size_t>(contact.wheel().lanes), sinkage_m);
  WheelWrench wrench;
  const int steps = static_cast<int>(std::lround(duration_s / kDt));
  for (int i = 0; i < steps; ++i) {
    const WheelKinematics kinematics{
        {0.0, 0.0, 0.3}, {0.0, 1.0, 0.0}, {speed, 0.0, 0.0}, spin_radps};
    wrench = contact.step(kinematics, kUp, lanes, kDt);
  }
  return wrench;
}

// The shear-displacement state reaches Wong–Reece's steady displacement: the rig's drawbar pull
// and load match the separate reference at the same sinkage, slip −0.2 … 0.8, within 0.2 % of the
// load (the transport sums the slip rate by the midpoint rule over 24 samples). The reference
// follows each soil element's elastoplastic path (its unloading ratio): where a towed wheel's
// soil is first sheared forward near the entry and then back, it unloads stiffly; everywhere
// else it is Janosi–Hanamoto of the total displacement.
TEST(WheelSoil, SteadyRollingReachesWongReeceAcrossSlip) {
  const SoilParams soil = dry_sand();
  for (const int samples : {24, 96}) {
    WheelGeometry wheel;
    wheel.bladed = false;
    wheel.arc_samples = samples;
    reference::Wheel reference_wheel{
        wheel.rim_radius_m, wheel.shear_radius_m(), wheel.width_m, 0.0, 1, false};
    for (int step = 0; step <= 10; ++step) {
      const double slip = -0.2 + 0.1 * step;
      const reference::Result expected =
          reference::at_load(reference_soil(soil), reference_wheel, kWheelLoadN, slip);
      WheelSoilContact contact(soil, wheel);
      const WheelWrench wrench = run_rig(contact, expected.sinkage_m, 2.0, slip, 1.0);
      // At 24 samples a towed wheel's unloading near the entry, a kink in the shear along the
      // arc, costs the midpoint rule up to 0.5 % of the load; at 96 it is within 0.2 % again.
      const double tolerance = samples == 24 && slip < 0.0 ? 0.006 : 0.002;
      EXPECT_NEAR(wrench.diagnostics.normal_load_n / expected.weight_n, 1.0, tolerance)
          << "slip " << slip << ", " << samples << " samples";
      EXPECT_NEAR(wrench.diagnostics.drawbar_pull_n / expected.weight_n,
                  expected.drawbar_pull_n / expected.weight_n, tolerance)
          << "slip " << slip << ", " << samples << " samples";
      EXPECT_NEAR(wrench.diagnostics.slip, slip, 1e-9);
      EXPECT_NEAR(wrench.sinkage_m, expected.sinkage_m, 1e-12);
    }
  }
}

// Spinning in place (Procedure 5.1's exterior wheels at their extreme): inclined blades push the
// wheel sideways, by handedness; blades across the axle and a smooth rim do not.
TEST(WheelSoil, LateralForceOfASpinningWheelWithAndWithoutBlades) {
  const double sinkage = 0.025;
  const auto lateral = [&](WheelGeometry wheel) {
    WheelSoilContact contact(dry_sand(), wheel);
    return run_rig(contact, sinkage, 2.0, 1.0, 0.5).diagnostics.lateral_n;
  };
  WheelGeometry right, left, straight, smooth;
  left.handedness = BladeHandedness::kLeft;
  straight.blade_inclination_rad = 0.0;
  smooth.bladed = false;
  // Spinning at a standstill both shears saturate and the along-blade friction (σ tan δ cos i)
  // outweighs the across-blade strength's sideways share ((c + σ tan φ) sin i): the right-handed
  // wheel is pushed toward +y by ≈ 1.2 N. At moderate slip the along-blade displacement (j sin i)
  // is still small and the across-blade share wins: toward −y (wheel_stress_test).
  const double pushed = lateral(right);
  EXPECT_GT(pushed, 0.005 * kWheelLoadN);
  EXPECT_DOUBLE_EQ(lateral(left), -pushed);
  EXPECT_NEAR(lateral(straight), 0.0, 1e-9);
  EXPECT_NEAR(lateral(smooth), 0.0, 1e-9);
}

// A wheel rolling with a sideways drift is resisted sideways by the shear and its leading side
// face's bulldozing, and more so the deeper it sinks.
TEST(WheelSoil, SidewaysDriftIsResistedByShearAndSidewall) {
  WheelGeometry smooth;
  smooth.bladed = false;
  double previous = 0.0;
  for (double sinkage : {0.01, 0.02, 0.04}) {
    WheelSoilContact contact(dry_sand(), smooth);
    const std::vector<double> lanes(3, sinkage);
    WheelWrench wrench;
    for (int i = 0; i < 500; ++i) {
      wrench =
          contact.step({{0.0, 0.0, 0.3}, {0.0, 1.0, 0.0}, {0.2, 0.05, 0.0}, 1.6}, kUp, lanes, kDt);
    }
    EXPECT_LT(wrench.diagnostics.lateral_n, previous) << "sinkage " << sinkage;
    EXPECT_LT(wrench.diagnostics.sidewall_n, 0.0);
    previous = wrench.diagnostics.lateral_n;
  }
}

// Procedure 5.1's criterion that the exterior wheels, which slide sideways in a spin, should turn
// faster (F̂ > 1): a wheel spinning faster resists being dragged sideways less. The rim carries
// the lateral displacement from the entry, j_y(θ) = −v_y (θ1 − θ)/ω, so at a higher spin less of
// it builds up under the wheel and less of the soil's lateral shear is mobilised. It is the
// shear's own kinematics: blades across the axle (i = 0) show it as well as inclined ones. The
// resistance is the mean of the forces against a drift either way (which cancels the inclined
// blades' own push); 2 cm deep, 5 cm/s sideways, not advancing.
TEST(WheelSoil, SpinningFasterLowersTheLateralResistance) {
  const auto resistance = [](const WheelGeometry& wheel, double spin_radps) {
    const auto force = [&](double lateral_mps) {
      WheelSoilContact contact(dry_sand(), wheel);
      const std::vector<double> lanes(3, 0.022);
      WheelWrench wrench;
      for (int i = 0; i < 2000; ++i) {
        const WheelKinematics kinematics{
            {0.0, 0.0, 0.3}, {0.0, 1.0, 0.0}, {0.0, lateral_mps, 0.0}, spin_radps};
        wrench = contact.step(kinematics, kUp, lanes, kDt);
      }
      return wrench.diagnostics.lateral_n;
    };
    return 0.5 * (force(-0.05) - force(0.05));
  };
  WheelGeometry inclined, straight;
  straight.blade_inclination_rad = 0.0;
  for (const WheelGeometry& wheel : {inclined, straight}) {
    const double slow = resistance(wheel, 0.5), fast = resistance(wheel, 2.0);
    EXPECT_GT(slow, 0.1 * kWheelLoadN) << "i = " << wheel.blade_inclination_rad;
    EXPECT_LT(fast, 0.7 * slow) << "i = " << wheel.blade_inclination_rad;
  }
}

// No slip ratio: a wheel standing in its bowl (the soil touching it all round, θ2 = −θ1) that
// has crept 2 mm downhill and then stands still (v = 0, ω = 0) keeps the holding force of a
// spring, step after step, instead of losing it with its speed.
TEST(WheelSoil, StillWheelIsHeldLikeASpring) {
  WheelSoilContact contact(dry_sand(), WheelGeometry{});
  const double sinkage = 0.025;
  const std::vector<double> lanes(3, sinkage);
  const std::vector<double> bowl(3, -std::acos(1.0 - sinkage / WheelGeometry{}.rim_radius_m));
  const double creep_mps = -0.002;  // 2 mm over a second
  const auto creep = [&] {
    for (int i = 0; i < 1000; ++i) {
      contact.step({{0.0, 0.0, 0.3}, {0.0, 1.0, 0.0}, {creep_mps, 0.0, 0.0}, 0.0}, kUp, lanes,
                   bowl, kDt);
    }
  };
  const WheelKinematics still{{0.0, 0.0, 0.3}, {0.0, 1.0, 0.0}, {0.0, 0.0, 0.0}, 0.0};
  creep();
  const double held = contact.step(still, kUp, lanes, bowl, kDt).diagnostics.drawbar_pull_n;
  EXPECT_GT(held, 0.05 * kWheelLoadN);  // uphill, against the creep
  for (int i = 0; i < 10000; ++i) {
    EXPECT_EQ(contact.step(still, kUp, lanes, bowl, kDt).diagnostics.drawbar_pull_n, held);
  }
  // Twice the creep holds more, but less than twice as much (Janosi–Hanamoto's saturation).
  creep();
  const double held_twice =
      contact.step(still, kUp, lanes, bowl, kDt).diagnostics.drawbar_pull_n;
  EXPECT_GT(held_twice, held);
  EXPECT_LT(held_twice, 2.0 * held);
}

// The tangential reload memory (SoilParams::tangential_reload_memory): a still wheel crept back
// 5 mm, then forward 0.2 mm (its soil unloads along the stiff line, ratio/K in the mobilised share
// per metre) and back 0.2 mm reloads along the same line to the very force it had: the loop
// closes. Without the memory the reload follows Janosi–Hanamoto's curve from the share the soil
// fell to, as fresh soil would, and holds less.
TEST(WheelSoil, SoilThatUnloadedReloadsAlongTheSameLine) {
  const double sinkage = 0.025;
  const std::vector<double> lanes(3, sinkage);
  const std::vector<double> bowl(3, -std::acos(1.0 - sinkage / WheelGeometry{}.rim_radius_m));
  const auto pull_after = [&](bool memory, double forward_m, double* before_n) {
    SoilParams sand = dry_sand();
    sand.tangential_reload_memory = memory;
    WheelSoilContact contact(sand, WheelGeometry{});
    const auto creep = [&](double speed_mps, double distance_m) {
      WheelWrench wrench;
      const int steps = static_cast<int>(std::lround(distance_m / std::abs(speed_mps) / kDt));
      for (int i = 0; i < steps; ++i) {
        wrench = contact.step({{0.0, 0.0, 0.3}, {0.0, 1.0, 0.0}, {speed_mps, 0.0, 0.0}, 0.0}, kUp,
                              lanes, bowl, kDt);
      }
      return wrench.diagnostics.drawbar_pull_n;
    };
    *before_n = creep(-0.002, 0.005);
    const double unloaded_n = creep(+0.002, forward_m);
    EXPECT_LT(unloaded_n, *before_n);
    return creep(-0.002, forward_m);
  };
  double before_n = 0.0, before_without_n = 0.0;
  const double reloaded_n = pull_after(true, 0.0002, &before_n);
  const double reloaded_without_n = pull_after(false, 0.0002, &before_without_n);
  EXPECT_GT(before_n, 0.1 * kWheelLoadN);  // uphill, against the creep
  EXPECT_EQ(before_n, before_without_n);   // first loading: the same curve
  EXPECT_NEAR(reloaded_n, before_n, 1e-9 * before_n);
  EXPECT_LT(reloaded_without_n, 0.95 * before_n);
}

// Vertical damping: a wheel sinking at 0.1 m/s is pushed up harder than a still one, by R·A·v; one
// rising fast is never pulled down into the soil.
TEST(WheelSoil, VerticalDampingResistsSinkingButNeverSucks) {
  const std::vector<double> lanes(3, 0.02);
  const auto normal = [&](double vertical_mps) {
    WheelSoilContact contact(dry_sand(), WheelGeometry{});
    return contact.step({{0, 0, 0.3}, {0, 1, 0}, {0, 0, vertical_mps}, 0.0}, kUp, lanes, kDt)
        .diagnostics.normal_load_n;
  };
  const double still = normal(0.0);
  const double area = std::acos(1.0 - 0.02 / 0.115) * 0.115 * 0.15;  // θ1·r·b, exit at 0
  EXPECT_NEAR(normal(-0.1) - still, 3e4 * area * 0.1, 1e-9);
  EXPECT_NEAR(normal(10.0), 0.0, 1e-9);
}

// Regular at and near rest: speeds of 1e-12 give finite forces, continuous with rest.
TEST(WheelSoil, RegularAtLowSpeed) {
  const std::vector<double> lanes(3, 0.02);
  WheelSoilContact at_rest(dry_sand(), WheelGeometry{});
  WheelSoilContact crawling(dry_sand(), WheelGeometry{});
  const WheelWrench rest = at_rest.step({{0, 0, 0.3}, {0, 1, 0}, {0, 0, 0}, 0.0}, kUp, lanes, kDt);
  const WheelWrench crawl =
      crawling.step({{0, 0, 0.3}, {0, 1, 0}, {1e-12, -1e-12, 0}, 1e-12}, kUp, lanes, kDt);
  for (int k = 0; k < 3; ++k) {
    EXPECT_TRUE(std::isfinite(crawl.force_n[static_cast<std::size_t>(k)]));
    EXPECT_NEAR(crawl.force_n[static_cast<std::size_t>(k)],
                rest.force_n[static_cast<std::size_t>(k)], 1e-6);
  }
  EXPECT_GT(rest.diagnostics.normal_load_n, 0.0);
}

// Driving backward is driving forward mirrored: the same pull, reversed, and the same load.
TEST(WheelSoil, ReverseIsTheMirrorImage) {
  WheelSoilContact forward(dry_sand(), WheelGeometry{});
  WheelSoilContact backward(dry_sand(), WheelGeometry{});
  const std::vector<double> lanes(3, 0.025);
  WheelWrench ahead, back;
  for (int i = 0; i < 800; ++i) {
    ahead = forward.step({{0, 0, 0.3}, {0, 1, 0}, {0.15, 0, 0}, 2.0}, kUp, lanes, kDt);
    back = backward.step({{0, 0, 0.3}, {0, 1, 0}, {-0.15, 0, 0}, -2.0}, kUp, lanes, kDt);
  }
  EXPECT_EQ(backward.direction(), -1);
  EXPECT_NEAR(back.diagnostics.drawbar_pull_n, -ahead.diagnostics.drawbar_pull_n, 1e-9);
  EXPECT_NEAR(back.diagnostics.normal_load_n, ahead.diagnostics.normal_load_n, 1e-9);
  EXPECT_NEAR(back.diagnostics.resisting_torque_nm, -ahead.diagnostics.resisting_torque_nm, 1e-9);
}

// The world frame: a wheel heading +y (axle along −x) gets the same wrench rotated by 90°.
TEST(WheelSoil, ForcesAreInTheWorldFrame) {
  WheelSoilContact along_x(dry_sand(), WheelGeometry{});
  WheelSoilContact along_y(dry_sand(), WheelGeometry{});
  const std::vector<double> lanes{0.02, 0.025, 0.03};
  WheelWrench a, b;
  for (int i = 0; i < 300; ++i) {
    a = along_x.step({{0, 0, 0.3}, {0, 1, 0}, {0.1, 0.01, 0}, 1.5}, kUp, lanes, kDt);
    b = along_y.step({{0, 0, 0.3}, {-1, 0, 0}, {-0.01, 0.1, 0}, 1.5}, kUp, lanes, kDt);
  }
  EXPECT_NEAR(b.force_n[0], -a.force_n[1], 1e-9);
  EXPECT_NEAR(b.force_n[1], a.force_n[0], 1e-9);
  EXPECT_NEAR(b.force_n[2], a.force_n[2], 1e-9);
  EXPECT_NEAR(b.torque_nm[0], -a.torque_nm[1], 1e-9);
  EXPECT_NEAR(b.torque_nm[1], a.torque_nm[0], 1e-9);
  EXPECT_NEAR(b.torque_nm[2], a.torque_nm[2], 1e-9);
  EXPECT_GT(std::abs(a.torque_nm[0]), 0.0);  // the deeper +y lane rolls the wheel
}

TEST(WheelSoil, SameInputsGiveIdenticalBits) {
  const auto run = [] {
    WheelSoilContact contact(dry_sand(), WheelGeometry{});
    std::vector<double> trace;
    for (int i = 0; i < 2000; ++i) {
      const double t = i * kDt;
      const std::vector<double> lanes{0.02 + 0.005 * std::sin(t), 0.022,
                                      0.018 + 0.004 * std::cos(3 * t)};
      const WheelWrench w = contact.step({{0, 0, 0.3},
                                          {0, 1, 0},
                                          {0.1 * std::sin(2 * t), 0.02 * std::cos(t), 0},
                                          2.0 * std::cos(t)},
                                         kUp, lanes, kDt);
      trace.insert(trace.end(), w.force_n.begin(), w.force_n.end());
      trace.insert(trace.end(), w.torque_nm.begin(), w.torque_nm.end());
    }
    return trace;
  };
  const std::vector<double> first = run(), second = run();
  ASSERT_EQ(first.size(), second.size());
  EXPECT_EQ(std::memcmp(first.data(), second.data(), first.size() * sizeof(double)), 0);
}

TEST(WheelSoil, RejectsBadInput) {
  WheelSoilContact contact(dry_sand(), WheelGeometry{});
  const std::vector<double> two(2, 0.01), three(3, 0.01);
  test_support::expect_invalid_argument([&] { contact.step({}, kUp, two, kDt); },
                                        {"expected 3 lane sinkages", "got 2"});
  test_support::expect_invalid_argument([&] { contact.step({}, kUp, three, two, kDt); },
                                        {"as many exit, front and entry angles", "got 3, 2, 0, 0"});
  test_support::expect_invalid_argument([&] { contact.step({}, kUp, three, three, two, kDt); },
                                        {"as many exit, front and entry angles", "got 3, 3, 2, 0"});
  test_support::expect_invalid_argument(
      [&] { contact.step({}, kUp, three, three, three, two, kDt); },
      {"as many exit, front and entry angles", "got 3, 3, 3, 2"});
  test_support::expect_invalid_argument([&] { contact.step({}, kUp, three, -1.0); }, {"dt_s >= 0"});
  SoilParams soil = dry_sand();
  soil.shear_modulus_m = -1.0;
  test_support::expect_invalid_argument([&] { WheelSoilContact bad(soil, WheelGeometry{}); },
                                        {"shear_modulus_m"});
}

}  // namespace
}  // namespace marsokhod::sim::soil
