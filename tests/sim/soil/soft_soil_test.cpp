#include "sim/soil/soft_soil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include "../../support/invalid_argument.hpp"
#include "sim/soil/wheel_stress.hpp"
#include "sim/soil/wide.hpp"

namespace marsokhod::sim::soil {
namespace {

constexpr double kWheelMassKg = 82.0 / 6.0;  // a sixth of the rover on each wheel
constexpr double kDt = 0.001;

SoftSoil one_wheel_on_flat_sand(double yield_period_s = SoftSoil::kYieldPeriodS) {
  return SoftSoil(dry_sand(), {-1.0, -0.3, 0.01, 300, 60}, [](double, double) { return 0.0; },
                  {WheelGeometry{}}, yield_period_s);
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

// The four-wide loops (wide.hpp) change nothing but the time: a wheel set down, then driven at
// 20 % slip through fresh soil and its own rut back, then pushed sideways to and fro (the lateral
// shear unloading at each turn) while it spins fast enough for its rim to move more than a sample
// a step, gives the same wrenches, bit for bit, as on the one- and two-wide forms alone.
TEST(SoftSoil, TheFourWideLoopGivesTheTwoWideFormsBits) {
  if (!wide::available()) GTEST_SKIP() << "no AVX2 here: the two-wide form does all the work";
  for (const bool memory : {false, true}) {  // the tangential reload memory off (default) and on
  SCOPED_TRACE(memory);
  const auto run = [memory](bool four_wide) {
    wide::use(four_wide);
    SoilParams sand = dry_sand();
    sand.tangential_reload_memory = memory;
    SoftSoil soil(sand, {-1.0, -0.3, 0.01, 300, 60}, [](double, double) { return 0.0; },
                  {WheelGeometry{}});
    std::vector<WheelWrench> trace;
    run_vertical_rig(soil, 0.0, 0.0, 0.5, &trace);
    run_vertical_rig(soil, 1.0, 0.1, 1.5, &trace);
    run_vertical_rig(soil, -1.0, -0.1, 1.0, &trace);
    double y = 0.0, z = 0.115, vz = 0.0;
    for (int i = 0; i < 1500; ++i) {
      const double lateral_mps = 0.05 * std::sin(0.02 * i);  // a turn every 157 ms
      const double spin_radps = i < 750 ? 1.0 : 40.0;
      const WheelKinematics wheel{{0.0, y, z}, {0.0, 1.0, 0.0}, {0.02, lateral_mps, vz},
                                  spin_radps};
      const std::vector<WheelWrench> wrenches = soil.step({&wheel, 1}, kDt);
      const double force = wrenches[0].force_n[2] - kWheelMassKg * 9.81 - 300.0 * vz;
      vz += force / kWheelMassKg * kDt;
      z += vz * kDt;
      y += lateral_mps * kDt;
      trace.push_back(wrenches[0]);
    }
    wide::use(true);
    return trace;
  };
  const std::vector<WheelWrench> four = run(true), two = run(false);
  ASSERT_EQ(four.size(), two.size());
  for (std::size_t i = 0; i < four.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      ASSERT_EQ(std::memcmp(&four[i].force_n[axis], &two[i].force_n[axis], sizeof(double)), 0)
          << "step " << i << ", force " << axis;
      ASSERT_EQ(std::memcmp(&four[i].torque_nm[axis], &two[i].torque_nm[axis], sizeof(double)), 0)
          << "step " << i << ", torque " << axis;
    }
  }
  EXPECT_GT(four.back().sinkage_m, 0.0);  // it ran in the soil
  }
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

// A still wheel in the bowl it pressed touches it all round, in either direction it may creep:
// the exit angle is −θ1 and the front angle θ1 both ways, and creeping at 2 mm/s it meets no
// more than its shear's small spring, the same both ways. On the rover's 2 cm cells, the wheel
// between two cell centres: the grid's bilinear bowl parts from the rim by up to cell²/(4r) =
// 0.87 mm there. With a touch tolerance of 0.1 mm the search found the rim clear of the soil just
// behind the bottom, the whole arc lay ahead and its pressure pushed the wheel back at each
// reversal: 0.08 of its load here (11 N), 0.37 under the rover's centre wheels, 3.9 cm deep, where
// it made a chatter the accelerometer read as 2.2 m/s² rms (rover_soft_soil_test). The contact's
// frame turns only once the arc has moved back K = 1 cm (wheel_soil.hpp): a creep of 10 µm keeps
// it, one of 1.1 cm turns it.
TEST(SoftSoil, AStillWheelInItsBowlTouchesItAllRound) {
  SoftSoil soil(dry_sand(), {-1.0, -0.3, 0.02, 100, 30}, [](double, double) { return 0.0; },
                {WheelGeometry{}});
  const double x = -0.507;  // between the centres of the cells at −0.51 and −0.49
  double z = 0.115, vz = 0.0;
  for (int i = 0; i < 2000; ++i) {  // set down: the vertical rig's damper, no travel
    const WheelKinematics wheel{{x, 0.0, z}, {0.0, 1.0, 0.0}, {0.0, 0.0, vz}, 0.0};
    const double force =
        soil.step({&wheel, 1}, kDt)[0].force_n[2] - kWheelMassKg * 9.81 - 300.0 * vz;
    vz += force / kWheelMassKg * kDt;
    z += vz * kDt;
  }
  const double load = kWheelMassKg * 9.81;
  for (const double speed : {0.002, -0.002}) {
    SoftSoil creeping = soil;
    const WheelKinematics wheel{{x, 0.0, z}, {0.0, 1.0, 0.0}, {speed, 0.0, 0.0}, 0.0};
    const SoftSoil::LaneContacts at_rest = creeping.lane_contacts(0, wheel);
    WheelWrench wrench;
    for (int i = 0; i < 5; ++i) wrench = creeping.step({&wheel, 1}, kDt)[0];
    const SoftSoil::LaneContacts lanes = creeping.lane_contacts(0, wheel);
    for (std::size_t lane = 0; lane < lanes.exit_rad.size(); ++lane) {
      const double entry = std::acos(1.0 - lanes.sinkage_m[lane] / 0.115);
      EXPECT_NEAR(lanes.exit_rad[lane], -entry, 1e-9) << "lane " << lane << ", " << speed << " m/s";
      EXPECT_NEAR(lanes.front_rad[lane], entry, 1e-9) << "lane " << lane << ", " << speed << " m/s";
      EXPECT_NEAR(at_rest.exit_rad[lane], -entry, 1e-9) << "lane " << lane;
      EXPECT_NEAR(at_rest.front_rad[lane], entry, 1e-9) << "lane " << lane;
    }
    EXPECT_EQ(creeping.contact(0).direction(), 1);
    EXPECT_GT(wrench.sinkage_m, 0.01);
    EXPECT_LT(std::abs(wrench.force_n[0]), 0.02 * load) << speed << " m/s";
    for (int i = 0; i < 5500; ++i) creeping.step({&wheel, 1}, kDt);  // 1.1 cm in all
    EXPECT_EQ(creeping.contact(0).direction(), speed > 0.0 ? 1 : -1) << speed << " m/s";
  }
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

// The grid yields once per period, with the blades' soil of every step since the last; raking
// it level starts the period again; a period of 0 yields every step. The blades carry soil out
// only once the rim has slipped past the soil by more than its elastic shear, K = 1 cm (the
// excavation's play, soft_soil.hpp): spinning in place at 2 rad/s the rim slips 2.5 mm a period,
// so the first four periods carry nothing out and from then on f_e·b·h·(slip − K).
TEST(SoftSoil, TheGridYieldsOncePerPeriod) {
  SoftSoil soil = one_wheel_on_flat_sand();
  // 1.5 cm into the sand, spinning at 2 rad/s in place.
  const WheelKinematics wheel{{0.0, 0.0, 0.10}, {0.0, 1.0, 0.0}, {0.0, 0.0, 0.0}, 2.0};
  const WheelGeometry geometry;
  const double slip_per_step = geometry.shear_radius_m() * 2.0 * kDt;
  const auto carried_m3 = [&](int steps) {  // all three lanes in
    return dry_sand().excavation_fraction * geometry.width_m * geometry.blade_height_m *
           std::max(steps * slip_per_step - dry_sand().shear_modulus_m, 0.0);
  };
  const auto steps_until_yield = [&] {
    for (int i = 1; i <= 20; ++i) {
      soil.step({&wheel, 1}, kDt);
      if (soil.yielded()) return i;
    }
    return 0;
  };
  EXPECT_EQ(steps_until_yield(), 10);
  EXPECT_GT(soil.grid().volumes().compacted_m3, 0.0);
  EXPECT_EQ(soil.grid().volumes().excavated_m3, 0.0);  // 2.5 mm of slip, within the play
  for (int period = 2; period <= 6; ++period) EXPECT_EQ(steps_until_yield(), 10);
  EXPECT_GT(carried_m3(60), 0.0);
  EXPECT_NEAR(soil.grid().volumes().excavated_m3, carried_m3(60), 1e-15);
  EXPECT_EQ(steps_until_yield(), 10);  // the seventh period
  EXPECT_NEAR(soil.grid().volumes().excavated_m3, carried_m3(70), 1e-15);
  for (int i = 0; i < 4; ++i) soil.step({&wheel, 1}, kDt);
  soil.level();  // raked: the 4 ms of spin since are forgotten, the play and the period start again
  EXPECT_EQ(soil.grid().volumes().cut_m3, 0.0);
  for (int period = 1; period <= 6; ++period) EXPECT_EQ(steps_until_yield(), 10);
  EXPECT_NEAR(soil.grid().volumes().excavated_m3, carried_m3(60), 1e-15);
  // Steps of 3 ms: it yields at the end of the step that ends within half a step of 10 ms, 9 ms.
  SoftSoil coarse = one_wheel_on_flat_sand();
  coarse.step({&wheel, 1}, 0.003);
  coarse.step({&wheel, 1}, 0.003);
  EXPECT_FALSE(coarse.yielded());
  coarse.step({&wheel, 1}, 0.003);
  EXPECT_TRUE(coarse.yielded());
  SoftSoil every_step = one_wheel_on_flat_sand(0.0);
  every_step.step({&wheel, 1}, kDt);
  EXPECT_TRUE(every_step.yielded());
  EXPECT_GT(every_step.grid().volumes().compacted_m3, 0.0);
}

// Yielding every 10 ms rather than every step: driving with slip, the wheel sinks as deep and the
// grid's books agree; spinning in place, the hole deepens as fast (5.6 cm in 3 s at 2 rad/s
// either way). Until the cells under a rim held still (2026-12-01) it deepened at 0.90 of the
// rate yielding every 10 ms (6.74 against 7.48 cm): between yields the repose slid the rim's soil
// back under the wheel, and the press cut it again, more often the more often it yielded.
TEST(SoftSoil, YieldingEvery10msAgainstYieldingEveryStep) {
  {
    SoftSoil every_step = one_wheel_on_flat_sand(0.0);
    SoftSoil every_period = one_wheel_on_flat_sand();
    const double z_step = run_vertical_rig(every_step, 2.0, 0.17, 3.0);
    const double z_period = run_vertical_rig(every_period, 2.0, 0.17, 3.0);
    const SoilVolumes& a = every_step.grid().volumes();
    const SoilVolumes& b = every_period.grid().volumes();
    EXPECT_NEAR(z_period, z_step, 5e-4);
    EXPECT_NEAR(b.excavated_m3 / a.excavated_m3, 1.0, 0.01);
    // As much compacted as the sinkage allows: the 0.5 mm it may differ by, (1 − f) of it
    // compacted under the 0.15 m wide rim over the 0.51 m it travels (measured: 0.986 against
    // 1.001 litres, the sinkage 0.3 mm apart).
    const double f = dry_sand().displaced_fraction;
    EXPECT_NEAR(b.compacted_m3, a.compacted_m3, (1.0 - f) * 5e-4 * 0.15 * 0.17 * 3.0);
  }
  SoftSoil every_step = one_wheel_on_flat_sand(0.0);
  SoftSoil every_period = one_wheel_on_flat_sand();
  const double dug_step = 0.115 - run_vertical_rig(every_step, 2.0, 0.0, 3.0);
  const double dug_period = 0.115 - run_vertical_rig(every_period, 2.0, 0.0, 3.0);
  EXPECT_NEAR(dug_period / dug_step, 1.0, 0.02);
  EXPECT_NEAR(every_period.grid().volumes().excavated_m3 / every_step.grid().volumes().excavated_m3,
              1.0, 0.01);
}

// The blades' spoil lands one cell behind the rim. Soil slides neither from under a wheel nor
// into the space under it (the cells it covers hold still), so a wheel spinning in place for 3 s
// piles its spoil against its own back (8.0 cm high, above its axle), and the repose spreads it
// backward and sideways: every pair of neighbours outside the wheel's shadow differs by no more
// than cell·tan 28° (and the last yield's spoil), so the pile holds at least the half diamond
// pyramid that slope leaves under its top against the wheel, h³/(3 tan² 28°): no higher than the
// ground's fill allows. (Before the cells under the wheel held still, the spoil slid back under it
// and stood below 3 cm; before the repose reached the landing cells, a one-cell tower of 0.36 m,
// 0.79 m yielding every 10 ms. A pile whose foot lay beyond the repose window stood there as
// against a wall: the window reaches as far as the pile's height at repose.)
TEST(SoftSoil, SpoilPilesBehindASpinningWheelAtTheAngleOfRepose) {
  const double slope = std::tan(dry_sand().repose_angle_rad);
  for (const double period : {0.0, SoftSoil::kYieldPeriodS}) {
    SCOPED_TRACE(period);
    SoftSoil soil = one_wheel_on_flat_sand(period);
    run_vertical_rig(soil, 2.0, 0.0, 3.0);
    const SoilGrid& grid = soil.grid();
    const double cell = grid.spec().cell_m;
    const auto shadowed = [&](int ix, int iy) {  // under the wheel: its centre (−0.5, 0)
      const double x = grid.spec().origin_x_m + (ix + 0.5) * cell + 0.5;
      const double y = grid.spec().origin_y_m + (iy + 0.5) * cell;
      return std::abs(x) < 0.115 + cell && std::abs(y) < 0.075 + cell;
    };
    double highest = 0.0, steepest = 0.0;
    for (int iy = 0; iy < 60; ++iy) {
      for (int ix = 0; ix < 300; ++ix) {
        const double h = grid.cell_surface_m(ix, iy);
        highest = std::max(highest, h);
        if (shadowed(ix, iy)) continue;
        if (ix + 1 < 300 && !shadowed(ix + 1, iy)) {
          steepest = std::max(steepest, std::abs(h - grid.cell_surface_m(ix + 1, iy)));
        }
        if (iy + 1 < 60 && !shadowed(ix, iy + 1)) {
          steepest = std::max(steepest, std::abs(h - grid.cell_surface_m(ix, iy + 1)));
        }
      }
    }
    EXPECT_GT(highest, 0.03);  // the spoil is there, against the wheel
    // The last yield's spoil has had only that yield's passes: it may stand above the slope by
    // as much as it raised the 15 landing cells across the wheel's 0.15 m.
    const double batch_m = grid.volumes().excavated_m3 / 3.0 * std::max(period, kDt) /
                           (15.0 * cell * cell);
    EXPECT_LE(steepest, cell * slope + batch_m);
    EXPECT_LE(highest * highest * highest, 3.0 * slope * slope * grid.earthwork().fill_m3);
  }
}

// A wheel that does not turn, dragged through fresh dry sand (a rigid wheel, Field Experiment
// 6.2): set down on the vertical rig, then carried along x at 5 cm/s without spinning. Dragged
// more than 10 K the shear is fully mobilised all along the arc, τ = c + σ tan φ against the
// motion (a smooth rim; with blades the same across them, δ along them). On a rim that slides
// forward the shear's force on the wheel points back along the rim's tangent and so down on the
// arc ahead of the bottom: the drag R = ∫(σ sin θ + τ cos θ) and the load W = ∫(σ cos θ − τ sin θ)
// (over r·b·dθ) give R − W tan φ = ∫σ sin θ + c∫cos θ + tan φ∫τ sin θ, positive on an arc that
// lies mostly ahead of the bottom: the wheel resists with more than tan φ = 0.53 of its load, and
// sinks deeper than it stood. With the blades, whose inclination i turns sin²i of the shear to the
// soil–metal friction along them, more than tan φ·cos²i + tan δ·sin²i = 0.52. (Measured: 1.08 of
// its load smooth, 1.16 bladed; it stood 1.3 cm deep and is dragged 2.45 cm deep.)
TEST(SoftSoil, AWheelDraggedWithoutTurningResistsWithMoreThanTheSoilsFriction) {
  const SoilParams sand = dry_sand();
  for (const bool bladed : {false, true}) {
    WheelGeometry wheel;
    wheel.bladed = bladed;
    SoftSoil soil(sand, {-1.0, -0.3, 0.01, 300, 60}, [](double, double) { return 0.0; }, {wheel});
    double x = -0.5, z = 0.115, vz = 0.0, standing_sinkage = 0.0, drag_n = 0.0;
    int averaged = 0;
    WheelWrench wrench;
    for (int i = 0; i < 6000; ++i) {  // 1 s set down, then 5 s (25 cm) dragged
      const double speed = i < 1000 ? 0.0 : 0.05;
      const WheelKinematics kinematics{{x, 0.0, z}, {0.0, 1.0, 0.0}, {speed, 0.0, vz}, 0.0};
      wrench = soil.step({&kinematics, 1}, kDt)[0];
      vz += (wrench.force_n[2] - kWheelMassKg * 9.81 - 300.0 * vz) / kWheelMassKg * kDt;
      z += vz * kDt;
      x += speed * kDt;
      if (i == 999) standing_sinkage = wrench.sinkage_m;
      if (i >= 5000) {  // the last second: 20–25 cm dragged
        drag_n -= wrench.force_n[0];
        ++averaged;
      }
    }
    const double load_n = kWheelMassKg * 9.81;
    const double i = wheel.blade_inclination_rad;
    const double friction =
        bladed ? std::tan(sand.friction_angle_rad) * std::cos(i) * std::cos(i) +
                     std::tan(sand.soil_metal_friction_angle_rad) * std::sin(i) * std::sin(i)
               : std::tan(sand.friction_angle_rad);
    EXPECT_GT(drag_n / averaged / load_n, friction) << (bladed ? "bladed" : "smooth");
    EXPECT_GT(wrench.sinkage_m, standing_sinkage + 0.002) << (bladed ? "bladed" : "smooth");
    EXPECT_NEAR(wrench.force_n[2], load_n, 0.05 * load_n);  // the rig carries it
  }
}

// A gait's anchor on a slope (rolking's centre stroke, docs/simulator.md "Rolking's anchors on a
// slope"): a wheel drives 16 cm (20 % slip), stands 1 s at the end of its rut, then is dragged
// back into the rut at 2 cm/s, as the slope's pull drags an anchor. Locked (not turning), the
// blades shear the soil under it: within 2 cm (2K) it resists with more than the soil's friction
// along the bladed rim, tan φ·cos² i + tan δ·sin² i = 0.515 (as dragged through fresh soil,
// above; 0.84–0.86 measured). Rolling back with its travel (the rim at the travel's speed, no
// slip) the blades shear nothing new: the shear the drive had loaded unloads, and it resists with
// less than that friction (0.30–0.33 at 2 cm, falling to the rut's compaction resistance, 0.16 at
// 6 cm). A light exterior wheel (59 N) and a sixth of the rover (134 N).
TEST(SoftSoil, AnAnchorHeldStillGripsWhereOneRollingBackGivesWay) {
  const SoilParams sand = dry_sand();
  const WheelGeometry geometry;
  const double i = geometry.blade_inclination_rad;
  const double friction = std::tan(sand.friction_angle_rad) * std::cos(i) * std::cos(i) +
                          std::tan(sand.soil_metal_friction_angle_rad) * std::sin(i) * std::sin(i);
  for (const double mass_kg : {6.0, kWheelMassKg}) {
    for (const bool rolling : {false, true}) {
      SCOPED_TRACE(mass_kg);
      SCOPED_TRACE(rolling);
      SoftSoil soil(sand, {-1.0, -0.3, 0.01, 300, 60}, [](double, double) { return 0.0; },
                    {geometry});
      const double rs = geometry.shear_radius_m();
      double x = -0.5, z = 0.115, vz = 0.0, start_x = 0.0, ratio = 0.0;
      for (int k = 0; k < 8000; ++k) {  // 1 s set down, 3 s driving, 1 s standing, 3 s back
        double speed = 0.0, spin = 0.0;
        if (k >= 1000 && k < 4000) {
          spin = 1.0;
          speed = 0.8 * rs * spin;
        } else if (k >= 5000) {
          speed = -0.02;
          spin = rolling ? speed / rs : 0.0;
        }
        if (k == 5000) start_x = x;
        const WheelKinematics wheel{{x, 0.0, z}, {0.0, 1.0, 0.0}, {speed, 0.0, vz}, spin};
        const WheelWrench w = soil.step({&wheel, 1}, kDt)[0];
        vz += (w.force_n[2] - mass_kg * 9.81 - 300.0 * vz) / mass_kg * kDt;
        z += vz * kDt;
        x += speed * kDt;
        if (k >= 5000 && start_x - x >= 0.02 && ratio == 0.0) {  // dragged back 2 cm
          ratio = w.force_n[0] / w.force_n[2];
        }
      }
      if (rolling) {
        EXPECT_LT(ratio, friction);
      } else {
        EXPECT_GT(ratio, friction);
      }
    }
  }
}

// An anchor the chassis shakes (docs/simulator.md, "The anchors' jitter"): a still wheel of
// 60 N on 16° of sand, dragged back down the slope at 1 cm/s after driving up it, keeps its grip
// when its drag carries a 15 Hz shake of ±3 cm/s (±0.3 mm, as the rover's anchors shook in
// rolking's strokes): the soil unloads and reloads along one stiff line. Without the tangential
// reload memory each shake's reversal unloaded the soil and the reload followed Janosi–Hanamoto's
// curve as from fresh soil, and the wheel slid at a fraction of its grip. (Measured: the smooth
// drag 0.99 of the load, shaken 0.85, shaken without the memory 0.16.)
TEST(SoftSoil, AStillWheelTheChassisShakesKeepsItsGrip) {
  const double slope = 16.0 * std::numbers::pi / 180.0;
  const auto mean_grip = [&](bool memory, double shake_mps) {
    SoilParams sand = dry_sand();
    sand.tangential_reload_memory = memory;
    const WheelGeometry geometry;
    SoftSoil soil(sand, {-1.0, -0.3, 0.02, 150, 30},
                  [slope](double x, double) { return x * std::tan(slope); }, {geometry});
    const double rs = geometry.shear_radius_m();
    const double load_n = 60.0, mass_kg = 6.0;
    double x = -0.5, z = 0.115 - 0.5 * std::tan(slope), vz = 0.0, start_x = 0.0;
    double along = 0.0, normal = 0.0;
    // 1 s set down, 3 s driving up at 3 cm/s (slip 0.3), 0.5 s spinning in place, then the drag.
    for (int k = 0; k < 10500; ++k) {
      double speed = 0.0, spin = 0.0;
      if (k >= 1000 && k < 4000) {
        speed = 0.03;
        spin = speed / 0.7 / rs;
      } else if (k >= 4000 && k < 4500) {
        spin = 0.013 / rs;
      } else if (k >= 4500) {
        speed = -0.01 + shake_mps * std::sin(2.0 * std::numbers::pi * 15.0 * (k - 4500) * kDt);
      }
      if (k == 4500) start_x = x;
      const WheelKinematics wheel{
          {x, 0.0, z}, {0.0, 1.0, 0.0}, {speed, 0.0, vz + speed * std::tan(slope)}, spin};
      const WheelWrench w = soil.step({&wheel, 1}, kDt)[0];
      vz += (w.force_n[2] - load_n - 300.0 * vz) / mass_kg * kDt;
      z += (vz + speed * std::tan(slope)) * kDt;
      x += speed * kDt;
      if (k > 4500 && start_x - x >= 0.02) {  // from 2 cm of drag on: the steady grip
        along += w.force_n[0] * std::cos(slope) + w.force_n[2] * std::sin(slope);
        normal += w.force_n[2] * std::cos(slope) - w.force_n[0] * std::sin(slope);
      }
    }
    return along / normal;
  };
  const double smooth = mean_grip(true, 0.0);
  const double shaken = mean_grip(true, 0.03);
  const double shaken_without = mean_grip(false, 0.03);
  EXPECT_GT(smooth, std::tan(dry_sand().friction_angle_rad));
  EXPECT_GT(shaken, 0.7 * smooth);
  EXPECT_LT(shaken_without, 0.3 * smooth);
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
  test_support::expect_invalid_argument([] { one_wheel_on_flat_sand(-0.001); },
                                        {"yield_period_s", "[0, 0.1]"});
  test_support::expect_invalid_argument([] { one_wheel_on_flat_sand(NAN); }, {"yield_period_s"});
  WheelGeometry bad;
  bad.width_m = -0.1;
  test_support::expect_invalid_argument(
      [&] { SoftSoil broken(dry_sand(), {}, [](double, double) { return 0.0; }, {bad}); },
      {"width_m"});
}

}  // namespace
}  // namespace marsokhod::sim::soil
