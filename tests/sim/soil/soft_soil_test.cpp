#include "sim/soil/soft_soil.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "../../support/invalid_argument.hpp"
#include "sim/soil/wheel_stress.hpp"

namespace marsokhod::sim::soil {
namespace {

constexpr double kWheelMassKg = 82.0 / 6.0;  // a sixth of the rover on each wheel
constexpr double kDt = 0.001;

SoftSoil one_wheel_on_flat_sand() {
  return SoftSoil(dry_sand(), {-1.0, -0.3, 0.01, 300, 60}, [](double, double) { return 0.0; },
                  {WheelGeometry{}});
}

// A vertical rig: the wheel free to move up and down only (a damper of 300 N·s/m stands in for the
// rover's suspension), spinning at spin_radps and carried along x at speed_mps. Returns the
// wheel's final centre height.
double run_vertical_rig(SoftSoil& soil, double spin_radps, double speed_mps, double duration_s,
                        std::vector<WheelWrench>* trace = nullptr) {
  double x = -0.5, z = 0.115, vz = 0.0;
  const int steps = static_cast<int>(std::lround(duration_s / kDt));
  for (int i = 0; i < steps; ++i) {
    const WheelKinematics wheel{{x, 0.0, z}, {0.0, 1.0, 0.0}, {speed_mps, 0.0, vz}, spin_radps};
    const std::vector<WheelWrench> wrenches = soil.step({&wheel, 1}, kDt);
    const double force = wrenches[0].force_n[2] - kWheelMassKg * 9.81 - 300.0 * vz;
    vz += force / kWheelMassKg * kDt;
    z += vz * kDt;
    x += speed_mps * kDt;
    if (trace != nullptr) trace->push_back(wrenches[0]);
  }
  return z;
}

// A wheel set down on flat sand settles where Bekker's plate pressure under every point of its rim
// carries its load: the contact is symmetric (the soil it pressed reaches up behind it as in
// front), so its sinkage is that of a front-only arc carrying half the load, and nothing pushes it
// along the ground. The rim rests where it pressed the soil (within its elastic rebound).
// (Within 2 %: the contact samples 2θ1 with 24 points where the reference samples θ1.)
TEST(SoftSoil, StandingWheelSettlesAtBekkersStaticSinkage) {
  SoftSoil soil = one_wheel_on_flat_sand();
  std::vector<WheelWrench> trace;
  const double z = run_vertical_rig(soil, 0.0, 0.0, 2.0, &trace);
  SoilParams plate = dry_sand();
  plate.max_stress_angle_c1 = 0.0;
  plate.max_stress_angle_c2 = 0.0;
  const double expected =
      equilibrium_sinkage_m(plate, WheelGeometry{}, 0.5 * kWheelMassKg * 9.81, 0.0);
  EXPECT_NEAR(trace.back().sinkage_m / expected, 1.0, 0.02);  // 24 samples over 2θ1, 3 lanes
  EXPECT_NEAR(trace.back().force_n[0], 0.0, 1e-6);
  EXPECT_NEAR(trace.back().force_n[2], kWheelMassKg * 9.81, 0.01);
  const double pressed = soil.grid().cell_sinkage_m(50, 30);
  EXPECT_GE(pressed, trace.back().sinkage_m);
  EXPECT_LT(0.115 - z, pressed + 1e-4);
}

// Driving across leaves a rut and a bank, with the grid's books balanced.
TEST(SoftSoil, DrivingLeavesARutAndConservesSoil) {
  SoftSoil soil = one_wheel_on_flat_sand();
  const double z = run_vertical_rig(soil, 2.0, 0.17, 4.0);
  EXPECT_LT(z, 0.115);
  const SoilGrid& grid = soil.grid();
  EXPECT_LT(grid.surface_m(-0.2, 0.0), -0.01);  // the rut behind the wheel
  double net = 0.0, highest = 0.0;
  for (int iy = 0; iy < 60; ++iy) {
    for (int ix = 0; ix < 300; ++ix) {
      net += (grid.cell_surface_m(ix, iy) - grid.cell_initial_m(ix, iy)) * 1e-4;
      highest = std::max(highest, grid.cell_surface_m(ix, iy));
    }
  }
  EXPECT_GT(highest, 0.002);  // the rut's banks
  const SoilVolumes& v = grid.volumes();
  EXPECT_NEAR(net, v.fill_m3 - v.cut_m3, 1e-10);
  EXPECT_NEAR(v.cut_m3 - v.fill_m3, v.compacted_m3, 1e-10);
  EXPECT_GT(v.compacted_m3, 0.0);
}

// Spinning on the spot, the blades carry soil out from under the wheel and it digs itself in
// (Field Experiment 5.2's trenching; the thesis' m4 dug up to 9 cm).
TEST(SoftSoil, SpinningInPlaceDigsAHole) {
  SoftSoil still = one_wheel_on_flat_sand();
  SoftSoil spinning = one_wheel_on_flat_sand();
  const double z_still = run_vertical_rig(still, 0.0, 0.0, 3.0);
  const double z_spinning = run_vertical_rig(spinning, 2.0, 0.0, 3.0);
  EXPECT_LT(z_spinning, z_still - 0.02);
  EXPECT_GT(spinning.grid().volumes().excavated_m3, 0.0);
  EXPECT_EQ(still.grid().volumes().excavated_m3, 0.0);
}

TEST(SoftSoil, SameInputsGiveIdenticalBits) {
  const auto run = [] {
    SoftSoil soil = one_wheel_on_flat_sand();
    std::vector<WheelWrench> trace;
    run_vertical_rig(soil, 2.0, 0.1, 1.5, &trace);
    std::vector<double> bits;
    for (const WheelWrench& w : trace) {
      bits.insert(bits.end(), w.force_n.begin(), w.force_n.end());
      bits.insert(bits.end(), w.torque_nm.begin(), w.torque_nm.end());
    }
    for (int iy = 0; iy < 60; ++iy) {
      for (int ix = 0; ix < 300; ++ix) bits.push_back(soil.grid().cell_surface_m(ix, iy));
    }
    return bits;
  };
  const std::vector<double> first = run(), second = run();
  ASSERT_EQ(first.size(), second.size());
  EXPECT_EQ(std::memcmp(first.data(), second.data(), first.size() * sizeof(double)), 0);
}

TEST(SoftSoil, RejectsBadInput) {
  SoftSoil soil = one_wheel_on_flat_sand();
  const std::vector<WheelKinematics> two(2);
  test_support::expect_invalid_argument([&] { soil.step(two, kDt); },
                                        {"expected 1 wheels", "got 2"});
  const std::vector<WheelKinematics> one(1);
  test_support::expect_invalid_argument([&] { soil.step(one, 0.0); }, {"dt_s > 0"});
  WheelGeometry bad;
  bad.width_m = -0.1;
  test_support::expect_invalid_argument(
      [&] { SoftSoil broken(dry_sand(), {}, [](double, double) { return 0.0; }, {bad}); },
      {"width_m"});
}

}  // namespace
}  // namespace marsokhod::sim::soil
