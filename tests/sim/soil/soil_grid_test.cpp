#include "sim/soil/soil_grid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include "../../support/invalid_argument.hpp"

namespace marsokhod::sim::soil {
namespace {

constexpr double kCellM = 0.01;

GridSpec small_grid() { return {-0.5, -0.3, kCellM, 100, 60}; }

double flat(double, double) { return 0.0; }

// Σ(surface − initial)·cell², the soil the grid gained.
double net_volume_m3(const SoilGrid& grid) {
  double volume = 0.0;
  for (int iy = 0; iy < grid.spec().cells_y; ++iy) {
    for (int ix = 0; ix < grid.spec().cells_x; ++ix) {
      volume += (grid.cell_surface_m(ix, iy) - grid.cell_initial_m(ix, iy)) * kCellM * kCellM;
    }
  }
  return volume;
}

void expect_balanced(const SoilGrid& grid) {
  const SoilVolumes& v = grid.volumes();
  EXPECT_NEAR(net_volume_m3(grid), v.fill_m3 - v.cut_m3, 1e-12);
  EXPECT_NEAR(v.cut_m3 - v.fill_m3, v.compacted_m3, 1e-12);
  // The earthwork's net is the books' net; its cut and fill are at most the books' (which also
  // count soil moved and moved back).
  const Earthwork e = grid.earthwork();
  EXPECT_NEAR(e.cut_m3 - e.fill_m3, v.compacted_m3, 1e-12);
  EXPECT_LE(e.cut_m3, v.cut_m3 + 1e-15);
  EXPECT_LE(e.fill_m3, v.fill_m3 + 1e-15);
}

// A wheel pressed 2 cm into flat sand: the cells under it go down to its rim, their plastic
// sinkage is the cut, half of the cut is compacted (displaced_fraction 0.5) and half raises the
// patch's rim; the undisturbed level under the wheel stays where it was.
TEST(SoilGrid, PressYieldsToTheRimAndConservesVolume) {
  SoilGrid grid(small_grid(), dry_sand(), flat);
  const Cylinder wheel{{0.0, 0.0, 0.115 - 0.02}, {0.0, 1.0, 0.0}, 0.115, 0.15};
  const Footprint footprint = grid.press(wheel);
  ASSERT_FALSE(footprint.contact_cells.empty());
  // The cell just below the wheel's lowest point (its centre 0.5 cm off): rim ≈ −0.02 m.
  const double rim = 0.095 - std::sqrt(0.115 * 0.115 - 0.005 * 0.005);
  EXPECT_NEAR(grid.cell_surface_m(50, 30), rim, 1e-12);
  EXPECT_NEAR(grid.cell_sinkage_m(50, 30), -rim, 1e-12);
  EXPECT_NEAR(grid.cell_compaction_m(50, 30), -0.5 * rim, 1e-12);
  EXPECT_NEAR(grid.undisturbed_m(0.005, 0.005), 0.0, 1e-12);
  EXPECT_GT(grid.volumes().compacted_m3, 0.0);
  EXPECT_NEAR(grid.volumes().fill_m3, grid.volumes().compacted_m3, 1e-15);
  expect_balanced(grid);
  // The rim: beside the wheel the surface rose.
  double beside = 0.0;
  for (int iy = 36; iy <= 39; ++iy) beside = std::max(beside, grid.cell_surface_m(50, iy));
  EXPECT_GT(beside, 0.0);
  // Pressing again at the same depth only re-presses the soil the rim received under the wheel's
  // arc, less each time, until nothing moves (the bank has left the wheel's way).
  double previous_cut = grid.volumes().cut_m3;
  for (int i = 0; i < 5; ++i) {
    const double cut_before = grid.volumes().cut_m3;
    grid.press(wheel);
    const double cut = grid.volumes().cut_m3 - cut_before;
    EXPECT_LE(cut, previous_cut);
    previous_cut = cut;
  }
  EXPECT_EQ(previous_cut, 0.0);
  expect_balanced(grid);
}

// The rut's depth and the compacted area read back what a press left: the wheel pressed 2 cm in
// cuts the cells under its lowest point (centres 0.5 cm off it) to the rim computed above; a box
// around the wheel finds that depth, a box beside it (only the raised rim) 0, a box between
// cell centres 0. The compacted cells lie in the contact patch, and compacted_m3 over their area
// is their mean compaction, at most half (displaced_fraction 0.5) of the 2 cm.
TEST(SoilGrid, DepthAndCompactedAreaReadTheRut) {
  SoilGrid grid(small_grid(), dry_sand(), flat);
  EXPECT_EQ(grid.max_depth_m(-0.5, -0.3, 0.5, 0.3), 0.0);
  EXPECT_EQ(grid.compacted_area_m2(), 0.0);
  EXPECT_EQ(grid.earthwork().cut_m3, 0.0);
  EXPECT_EQ(grid.earthwork().fill_m3, 0.0);
  const Cylinder wheel{{0.0, 0.0, 0.115 - 0.02}, {0.0, 1.0, 0.0}, 0.115, 0.15};
  const Footprint footprint = grid.press(wheel);
  const double rim = 0.095 - std::sqrt(0.115 * 0.115 - 0.005 * 0.005);
  EXPECT_NEAR(grid.max_depth_m(-0.1, -0.1, 0.1, 0.1), -rim, 1e-12);
  EXPECT_EQ(grid.max_depth_m(-0.1, 0.12, 0.1, 0.2), 0.0);
  EXPECT_EQ(grid.max_depth_m(0.001, 0.001, 0.004, 0.004), 0.0);  // no cell centre inside
  EXPECT_EQ(grid.max_depth_m(5.0, 5.0, 6.0, 6.0), 0.0);          // beyond the grid
  const double area = grid.compacted_area_m2();
  EXPECT_GT(area, 0.0);
  EXPECT_LE(area, static_cast<double>(footprint.contact_cells.size()) * kCellM * kCellM);
  const double mean_compaction = grid.volumes().compacted_m3 / area;
  EXPECT_GT(mean_compaction, 0.0);
  EXPECT_LE(mean_compaction, 0.5 * 0.02 + 1e-12);
  // The first press moved no soil twice: the earthwork is the books.
  EXPECT_NEAR(grid.earthwork().cut_m3, grid.volumes().cut_m3, 1e-15);
  EXPECT_NEAR(grid.earthwork().fill_m3, grid.volumes().fill_m3, 1e-15);
  expect_balanced(grid);
}

// Soil that slides back into a pressed rut lies loose on it (docs/simulator.md, "The undisturbed
// level in a rut"): it fills the rut's sinkage, so the level Bekker's z is measured from, surface +
// plastic sinkage, stays the ground's, and pressing or carrying it away gives the depth back. A
// cell's sinkage therefore never exceeds its depth below the initial surface
// (max_sinkage_excess_m() stays 0, where the grid before 2026-12-01 let it grow by the height
// laid).
TEST(SoilGrid, SoilLaidBackIntoAPressedRutLiesLooseOnIt) {
  SoilGrid grid(small_grid(), dry_sand(), flat);
  const Cylinder wheel{{0.0, 0.0, 0.115 - 0.02}, {0.0, 1.0, 0.0}, 0.115, 0.15};
  const Footprint footprint = grid.press(wheel);
  EXPECT_EQ(grid.max_sinkage_excess_m(), 0.0);
  std::vector<double> pressed(static_cast<std::size_t>(100 * 60));
  for (int iy = 0; iy < 60; ++iy) {
    for (int ix = 0; ix < 100; ++ix) {
      pressed[static_cast<std::size_t>(iy * 100 + ix)] = grid.cell_surface_m(ix, iy);
    }
  }
  // A bank 5 cm high just ahead of the rut's end (the footprint reaches x ≈ ±6.7 cm, cell 56),
  // slid to the angle of repose.
  grid.set_cell_surface_m(59, 30, 0.05);
  grid.relax(CellBox{57, 28, 61, 32}, 3, 50);
  double rise = 0.0;
  int rx = 0, ry = 0;
  for (int iy = 0; iy < 60; ++iy) {
    for (int ix = 0; ix < 100; ++ix) {
      const double before = pressed[static_cast<std::size_t>(iy * 100 + ix)];
      const double now = grid.cell_surface_m(ix, iy);
      if (before < -0.005 && now <= 0.0 && now - before > rise) {
        rise = now - before;
        rx = ix;
        ry = iy;
      }
    }
  }
  ASSERT_GT(rise, 0.001);  // the slide reached the rut
  const double depth = -pressed[static_cast<std::size_t>(ry * 100 + rx)];
  // The slide lies loose in the rut: the level Bekker's z is measured from stays the ground's,
  // and the sinkage left is the depth below it.
  EXPECT_NEAR(grid.cell_loose_m(rx, ry), rise, 1e-12);
  EXPECT_NEAR(grid.cell_sinkage_m(rx, ry), depth - rise, 1e-12);
  EXPECT_NEAR(grid.cell_surface_m(rx, ry) + grid.cell_sinkage_m(rx, ry), 0.0, 1e-12);
  EXPECT_NEAR(grid.max_sinkage_excess_m(), 0.0, 1e-12);
  // Where the slide overfilled a shallow part of the rut, the soil above the ground's level
  // raised that level (a pile on the ground), and the rut beneath is loose soil.
  int ox = -1, oy = -1;
  for (int cell : footprint.contact_cells) {
    const int ix = cell % 100, iy = cell / 100;
    if (grid.cell_surface_m(ix, iy) > 0.001 && (ox < 0 || grid.cell_surface_m(ix, iy) <
                                                              grid.cell_surface_m(ox, oy))) {
      ox = ix;
      oy = iy;
    }
  }
  ASSERT_GE(ox, 0);
  const double pile = grid.cell_surface_m(ox, oy);
  const double filled = -pressed[static_cast<std::size_t>(oy * 100 + ox)];
  EXPECT_EQ(grid.cell_sinkage_m(ox, oy), 0.0);
  EXPECT_NEAR(grid.cell_loose_m(ox, oy), filled, 1e-12);
  // Carried away again (the blades excavate half the rise from every cell of the patch), soil
  // goes from the top: in the rut it gives its depth back to the sinkage; on the overfilled cell
  // the pile goes first, lowering the level to the ground's, and only the rest comes from the rut.
  const double dug = 0.5 * rise;
  ASSERT_GT(dug, pile);
  const double spoil = dug * kCellM * kCellM * static_cast<double>(footprint.contact_cells.size());
  grid.excavate(footprint, wheel, {1.0, 0.0, 0.0}, 0.13, spoil);
  EXPECT_NEAR(grid.cell_loose_m(rx, ry), rise - dug, 1e-12);
  EXPECT_NEAR(grid.cell_sinkage_m(rx, ry), depth - rise + dug, 1e-12);
  EXPECT_NEAR(grid.cell_sinkage_m(ox, oy), dug - pile, 1e-12);
  EXPECT_NEAR(grid.cell_loose_m(ox, oy), filled - (dug - pile), 1e-12);
  EXPECT_NEAR(grid.cell_surface_m(ox, oy) + grid.cell_sinkage_m(ox, oy), 0.0, 1e-12);
  // Pressed again to the same rim, the rest is pressed: the cell is where it was, as deep. The
  // pile the slide left on unpressed ground at the rut's end is pressed too, from its top (a bank
  // bears as unpressed soil): its sinkage then exceeds its depth below the initial surface by at
  // most the pile's height, and the excess says so.
  double highest_pile = 0.0;  // the flat ground's initial level is 0
  for (int iy = 0; iy < 60; ++iy) {
    for (int ix = 0; ix < 100; ++ix) {
      highest_pile = std::max(highest_pile, grid.cell_surface_m(ix, iy));
    }
  }
  grid.press(wheel);
  EXPECT_NEAR(grid.cell_surface_m(rx, ry), -depth, 1e-12);
  EXPECT_NEAR(grid.cell_sinkage_m(rx, ry), depth, 1e-12);
  EXPECT_NEAR(grid.cell_loose_m(rx, ry), 0.0, 1e-12);
  EXPECT_NEAR(grid.cell_surface_m(rx, ry) + grid.cell_sinkage_m(rx, ry), 0.0, 1e-12);
  EXPECT_LE(grid.max_sinkage_excess_m(), highest_pile + 1e-12);
  // The window keeps a cell's loose soil as it moves; the rake clears it.
  grid.set_cell_surface_m(59, 30, 0.05);
  grid.relax(CellBox{57, 28, 61, 32}, 3, 50);
  int lx = 0, ly = 0;
  for (int iy = 0; iy < 60; ++iy) {
    for (int ix = 0; ix < 100; ++ix) {
      if (grid.cell_loose_m(ix, iy) > grid.cell_loose_m(lx, ly)) {
        lx = ix;
        ly = iy;
      }
    }
  }
  const double loose = grid.cell_loose_m(lx, ly);
  ASSERT_GT(loose, 0.001);
  ASSERT_GE(lx, 5);
  grid.shift(5, 0);
  EXPECT_EQ(grid.cell_loose_m(lx - 5, ly), loose);
  grid.level();
  EXPECT_EQ(grid.cell_loose_m(lx - 5, ly), 0.0);
}

// A rim standing on its contact cells holds them: relaxing with them held moves no soil into or
// out of them, though a bank beside them slides to the angle of repose.
TEST(SoilGrid, RelaxationLeavesTheCellsUnderARimAlone) {
  SoilGrid grid(small_grid(), dry_sand(), flat);
  const Cylinder wheel{{0.0, 0.0, 0.115 - 0.02}, {0.0, 1.0, 0.0}, 0.115, 0.15};
  const Footprint footprint = grid.press(wheel);
  std::vector<double> under;
  for (int cell : footprint.contact_cells) {
    under.push_back(grid.cell_surface_m(cell % 100, cell / 100));
  }
  grid.set_cell_surface_m(59, 30, 0.05);
  grid.relax(CellBox{57, 28, 61, 32}, 3, 50, &footprint);
  EXPECT_LT(grid.cell_surface_m(59, 30), 0.05 - 0.01);  // the bank slid
  for (std::size_t k = 0; k < under.size(); ++k) {
    const int cell = footprint.contact_cells[k];
    EXPECT_EQ(grid.cell_surface_m(cell % 100, cell / 100), under[k]) << "cell " << cell;
  }
  expect_balanced(grid);
}

// The bench's rake (RoverPhysics::level_soil): after a press and an excavation, level() puts every
// cell back at its initial surface with no sinkage or compaction, and the books start again.
TEST(SoilGrid, LevelRakesEveryCellBackToItsInitialSurface) {
  SoilGrid grid(small_grid(), dry_sand(), [](double x, double) { return 0.1 * x; });
  const Cylinder wheel{{0.0, 0.0, 0.115 - 0.02}, {0.0, 1.0, 0.0}, 0.115, 0.15};
  const Footprint footprint = grid.press(wheel);
  grid.excavate(footprint, wheel, {1.0, 0.0, 0.0}, 0.13, 1e-5);
  grid.relax(footprint, 3, 4);
  ASSERT_GT(grid.volumes().cut_m3, 0.0);
  grid.level();
  for (int iy = 0; iy < grid.spec().cells_y; ++iy) {
    for (int ix = 0; ix < grid.spec().cells_x; ++ix) {
      EXPECT_EQ(grid.cell_surface_m(ix, iy), grid.cell_initial_m(ix, iy));
      EXPECT_EQ(grid.cell_sinkage_m(ix, iy), 0.0);
      EXPECT_EQ(grid.cell_compaction_m(ix, iy), 0.0);
    }
  }
  EXPECT_EQ(grid.volumes().cut_m3, 0.0);
  EXPECT_EQ(grid.volumes().fill_m3, 0.0);
  EXPECT_EQ(grid.volumes().excavated_m3, 0.0);
}

// A 10 cm column of sand slumps until no two neighbours differ by more than cell·tan(repose),
// with every cubic millimetre accounted for.
// The window moves by whole cells: the cells it keeps hold their state at the same place on the
// ground, the cells it takes in are undisturbed at the initial surface there, and the cells it
// leaves behind keep their share of the books (earthwork, compacted area, deepest cut) though
// their ruts are gone when the window comes back over them. Raking clears those books too.
TEST(SoilGrid, ShiftMovesTheWindowAndKeepsTheBooks) {
  const auto tilted = [](double x, double y) { return 0.1 * x + 0.05 * y; };
  SoilGrid grid(small_grid(), dry_sand(), tilted);
  grid.press({{0.0, 0.0, 0.115 - 0.02}, {0.0, 1.0, 0.0}, 0.115, 0.15});
  const SoilGrid before = grid;
  const Earthwork work = grid.earthwork();
  const double area = grid.compacted_area_m2();
  const double deepest = grid.deepest_m();
  ASSERT_GT(deepest, 0.015);
  ASSERT_GT(area, 0.0);
  grid.clear_changed();

  grid.shift(3, -2);
  const GridSpec& spec = grid.spec();
  EXPECT_NEAR(spec.origin_x_m, -0.5 + 3 * kCellM, 1e-15);
  EXPECT_NEAR(spec.origin_y_m, -0.3 - 2 * kCellM, 1e-15);
  const CellBox changed = grid.changed();
  EXPECT_EQ(changed.min_x, 0);
  EXPECT_EQ(changed.min_y, 0);
  EXPECT_EQ(changed.max_x, spec.cells_x - 1);
  EXPECT_EQ(changed.max_y, spec.cells_y - 1);
  for (int iy = 0; iy < spec.cells_y; ++iy) {
    for (int ix = 0; ix < spec.cells_x; ++ix) {
      const int from_x = ix + 3, from_y = iy - 2;
      if (from_x < spec.cells_x && from_y >= 0) {
        ASSERT_EQ(grid.cell_surface_m(ix, iy), before.cell_surface_m(from_x, from_y));
        ASSERT_EQ(grid.cell_initial_m(ix, iy), before.cell_initial_m(from_x, from_y));
        ASSERT_EQ(grid.cell_sinkage_m(ix, iy), before.cell_sinkage_m(from_x, from_y));
        ASSERT_EQ(grid.cell_compaction_m(ix, iy), before.cell_compaction_m(from_x, from_y));
      } else {
        const double x = spec.origin_x_m + (ix + 0.5) * kCellM;
        const double y = spec.origin_y_m + (iy + 0.5) * kCellM;
        ASSERT_NEAR(grid.cell_surface_m(ix, iy), tilted(x, y), 1e-15) << ix << ", " << iy;
        ASSERT_EQ(grid.cell_initial_m(ix, iy), grid.cell_surface_m(ix, iy));
        ASSERT_EQ(grid.cell_sinkage_m(ix, iy), 0.0);
        ASSERT_EQ(grid.cell_compaction_m(ix, iy), 0.0);
      }
    }
  }
  // The same ground under the same world point.
  EXPECT_NEAR(grid.surface_m(0.003, 0.002), before.surface_m(0.003, 0.002), 1e-15);
  EXPECT_NEAR(grid.undisturbed_m(0.003, 0.002), before.undisturbed_m(0.003, 0.002), 1e-15);
  EXPECT_NEAR(grid.earthwork().cut_m3, work.cut_m3, 1e-15);
  EXPECT_NEAR(grid.earthwork().fill_m3, work.fill_m3, 1e-15);

  // Far away: every cell left behind, the books kept; back again: undisturbed ground.
  grid.shift(-200, 0);
  EXPECT_NEAR(grid.earthwork().cut_m3, work.cut_m3, 1e-15);
  EXPECT_NEAR(grid.earthwork().fill_m3, work.fill_m3, 1e-15);
  EXPECT_NEAR(grid.compacted_area_m2(), area, 1e-15);
  EXPECT_EQ(grid.deepest_m(), deepest);
  EXPECT_EQ(grid.max_depth_m(-10.0, -10.0, 10.0, 10.0), 0.0);  // nothing in the window
  grid.shift(197, 2);
  EXPECT_NEAR(grid.spec().origin_x_m, -0.5, 1e-12);
  EXPECT_NEAR(grid.spec().origin_y_m, -0.3, 1e-12);
  EXPECT_NEAR(grid.surface_m(0.0, 0.0), tilted(0.0, 0.0), 1e-12);  // the rut is forgotten
  EXPECT_EQ(grid.cell_sinkage_m(50, 30), 0.0);
  EXPECT_NEAR(grid.earthwork().cut_m3, work.cut_m3, 1e-15);
  EXPECT_EQ(grid.volumes().compacted_m3, before.volumes().compacted_m3);

  grid.level();
  EXPECT_EQ(grid.earthwork().cut_m3, 0.0);
  EXPECT_EQ(grid.earthwork().fill_m3, 0.0);
  EXPECT_EQ(grid.compacted_area_m2(), 0.0);
  EXPECT_EQ(grid.deepest_m(), 0.0);
}

// A surface that is not finite where the window moves to is refused, naming the cell, and the
// window stays where it was, as it was.
TEST(SoilGrid, ShiftRefusesANonFiniteSurface) {
  SoilGrid grid(small_grid(), dry_sand(),
                [](double x, double) { return x < 1.0 ? 0.0 : std::nan(""); });
  grid.press({{0.0, 0.0, 0.115 - 0.02}, {0.0, 1.0, 0.0}, 0.115, 0.15});
  const SoilGrid before = grid;
  test_support::expect_invalid_argument([&] { grid.shift(100, 0); },
                                        {"the initial surface at cell (", "finite"});
  EXPECT_EQ(grid.spec().origin_x_m, before.spec().origin_x_m);
  EXPECT_EQ(grid.cell_surface_m(50, 30), before.cell_surface_m(50, 30));
  EXPECT_EQ(grid.earthwork().cut_m3, before.earthwork().cut_m3);
}

TEST(SoilGrid, SlopesRelaxToTheAngleOfRepose) {
  Footprint window;
  window.min_x = window.max_x = 50;
  window.min_y = window.max_y = 30;
  // A pile made by excavation: 10 cm on one cell.
  SoilGrid piled(small_grid(), dry_sand(), [](double x, double y) {
    return (std::abs(x - 0.005) < 0.004 && std::abs(y - 0.005) < 0.004) ? 0.1 : 0.0;
  });
  const double before = net_volume_m3(piled);
  piled.relax(window, 20, 500);
  const double limit = kCellM * std::tan(dry_sand().repose_angle_rad);
  for (int iy = 10; iy < 50; ++iy) {
    for (int ix = 30; ix < 70; ++ix) {
      EXPECT_LE(std::abs(piled.cell_surface_m(ix + 1, iy) - piled.cell_surface_m(ix, iy)),
                limit + 1e-9);
      EXPECT_LE(std::abs(piled.cell_surface_m(ix, iy + 1) - piled.cell_surface_m(ix, iy)),
                limit + 1e-9);
    }
  }
  EXPECT_NEAR(net_volume_m3(piled), before, 1e-15);
  EXPECT_GT(piled.volumes().relaxed_m3, 0.0);
  EXPECT_EQ(piled.volumes().cut_m3, piled.volumes().fill_m3);
  EXPECT_LT(piled.cell_surface_m(50, 30), 0.1);
}

// A slope gentler than the angle of repose stays as it is.
TEST(SoilGrid, SlopesBelowReposeStay) {
  const double slope = std::tan(20.0 * std::numbers::pi / 180.0);
  SoilGrid grid(small_grid(), dry_sand(), [&](double x, double) { return x * slope; });
  Footprint window{{}, 10, 10, 90, 50, {}};
  grid.relax(window, 0, 10);
  EXPECT_EQ(grid.volumes().relaxed_m3, 0.0);
  const Vec3 normal = grid.normal(0.1, 0.0, 0.23);
  EXPECT_NEAR(normal[0], -std::sin(20.0 * std::numbers::pi / 180.0), 1e-9);
  EXPECT_NEAR(normal[1], 0.0, 1e-12);
  EXPECT_NEAR(grid.surface_m(0.123, 0.05), 0.123 * slope, 1e-12);
}

// Excavation carries soil from under the wheel to behind it: cut = fill, nothing compacted.
TEST(SoilGrid, ExcavationMovesSoilBehindTheWheel) {
  SoilGrid grid(small_grid(), dry_sand(), flat);
  const Cylinder wheel{{0.0, 0.0, 0.105}, {0.0, 1.0, 0.0}, 0.115, 0.15};
  const Footprint footprint = grid.press(wheel);
  ASSERT_FALSE(footprint.contact_cells.empty());
  grid.excavate(footprint, wheel, {1.0, 0.0, 0.0}, 0.125, 1e-5);
  EXPECT_NEAR(grid.volumes().excavated_m3, 1e-5, 1e-18);
  EXPECT_LT(grid.surface_m(0.005, 0.005), 0.0);
  EXPECT_GT(grid.cell_surface_m(50 - 13, 30), 0.0);  // 12.5 cm behind
  expect_balanced(grid);
}

// changed() bounds every cell whose surface moved since the last clear (what the physics copies
// into its height field): after construction and level() the whole grid; after a press, an
// excavation and the repose around them — each on its own, cleared in between, so that none
// leans on another's box — a box that holds each moved cell and is not the grid.
TEST(SoilGrid, ChangedBoxHoldsEveryCellThatMoved) {
  SoilGrid grid(small_grid(), dry_sand(), flat);
  const auto whole = [&](const CellBox& box) {
    return box.min_x == 0 && box.min_y == 0 && box.max_x == grid.spec().cells_x - 1 &&
           box.max_y == grid.spec().cells_y - 1;
  };
  EXPECT_TRUE(whole(grid.changed()));
  grid.clear_changed();
  EXPECT_TRUE(grid.changed().empty());
  std::vector<double> before;
  const auto take = [&] {
    before.clear();
    for (int iy = 0; iy < grid.spec().cells_y; ++iy) {
      for (int ix = 0; ix < grid.spec().cells_x; ++ix) {
        before.push_back(grid.cell_surface_m(ix, iy));
      }
    }
    grid.clear_changed();
  };
  const auto expect_inside = [&](const char* what) {
    const CellBox box = grid.changed();
    int moved = 0;
    for (int iy = 0; iy < grid.spec().cells_y; ++iy) {
      for (int ix = 0; ix < grid.spec().cells_x; ++ix) {
        if (grid.cell_surface_m(ix, iy) == before[static_cast<std::size_t>(iy * 100 + ix)]) {
          continue;
        }
        ++moved;
        EXPECT_TRUE(ix >= box.min_x && ix <= box.max_x && iy >= box.min_y && iy <= box.max_y)
            << what << ": " << ix << ", " << iy;
      }
    }
    EXPECT_GT(moved, 0) << what;
    EXPECT_FALSE(whole(box)) << what;
  };
  // A wheel 3 cm deep digging: soil pressed to the rim and pushed to its rim cells, carried
  // 12.5 cm behind, slid to repose.
  const Cylinder wheel{{0.0, 0.0, 0.085}, {0.0, 1.0, 0.0}, 0.115, 0.15};
  take();
  const Footprint footprint = grid.press(wheel);
  expect_inside("press");
  take();
  grid.excavate(footprint, wheel, {1.0, 0.0, 0.0}, 0.125, 2e-4);
  expect_inside("excavate");
  take();
  grid.relax(footprint, 3, 4);
  expect_inside("relax");
  EXPECT_GT(grid.volumes().relaxed_m3, 0.0);
  grid.level();
  EXPECT_TRUE(whole(grid.changed()));
}

TEST(SoilGrid, SamePressesGiveIdenticalBits) {
  const auto run = [] {
    SoilGrid grid(small_grid(), dry_sand(), flat);
    for (int i = 0; i < 200; ++i) {
      const Cylinder wheel{{-0.2 + 0.002 * i, 0.01 * std::sin(i * 0.1), 0.1 - 0.0001 * i},
                           {0.0, 1.0, 0.0},
                           0.115,
                           0.15};
      const Footprint footprint = grid.press(wheel);
      grid.excavate(footprint, wheel, {1.0, 0.0, 0.0}, 0.125, 1e-7);
      grid.relax(footprint, 3, 4);
    }
    std::vector<double> surface;
    for (int iy = 0; iy < 60; ++iy) {
      for (int ix = 0; ix < 100; ++ix) surface.push_back(grid.cell_surface_m(ix, iy));
    }
    return surface;
  };
  const std::vector<double> first = run(), second = run();
  EXPECT_EQ(std::memcmp(first.data(), second.data(), first.size() * sizeof(double)), 0);
}

TEST(SoilGrid, RejectsBadSpecs) {
  GridSpec spec = small_grid();
  spec.cell_m = 0.5;
  test_support::expect_invalid_argument([&] { SoilGrid grid(spec, dry_sand(), flat); },
                                        {"soil grid", "cell_m", "0.5"});
  spec = small_grid();
  spec.cells_x = 1;
  test_support::expect_invalid_argument([&] { SoilGrid grid(spec, dry_sand(), flat); },
                                        {"cells_x", "got 1"});
  test_support::expect_invalid_argument(
      [&] {
        SoilGrid grid(small_grid(), dry_sand(), [](double, double) { return test_support::kNaN; });
      },
      {"initial surface", "finite"});
}

}  // namespace
}  // namespace marsokhod::sim::soil
