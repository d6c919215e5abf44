// A deformable soil height grid, SCM-style (Soil Contact Model: Krenn and Hirzinger, 2009): square
// cells of side cell_m, each with
//   surface_m      the soil's current level (world z),
//   sinkage_m      the plastic sinkage: how deep rims have pressed the cell down in all,
//   compaction_m   the part of that sinkage by which the soil was compacted in place,
//   loose_m        the loose soil lying in the cell's rut, laid there after it was pressed,
//   above_m        the loose soil laid on it above its undisturbed level (a bank; sinkage_m is 0).
// surface_m + sinkage_m is the undisturbed level from which Bekker's sinkage z is measured, so a
// wheel resting in its own rut is carried as at the moment it pressed it. That level less above_m
// is the ground's, whose slope orients a wheel's frame (normal): the banks a wheel pushes up
// beside its rut do not tilt it.
//
// Loose soil (lay, take): soil laid on a cell (the rim's share of a press, spoil, a slide) first
// fills its rut: that height moves from sinkage_m to loose_m, so the undisturbed level stays the
// ground's (soil sliding back into a rut is loose soil in it, not pressed ground raised); what
// rises above the undisturbed level raises it, as a pile on unpressed ground does (above_m). Soil
// is taken from a cell's top (excavated, slid off): the pile above first, lowering the level with
// it, then the rut's loose soil, which gives its depth back to the sinkage, then the ground. A
// press that cuts a cell presses its loose soil with the rest (where soil lay above the
// undisturbed level, all of it: the level the press starts from).
//
// Contact (press): a cell touches the rim while the rim is no higher above it than its elastic
// rebound, sinkage_m / unloading_stiffness_ratio (0.1 mm at least).
// Plastic flow (press): a cell whose surface lies above the rim is cut down to the rim: the cut
// depth d adds to sinkage_m; (1 − f)·d to compaction_m, and f·d (f = displaced_fraction) is pushed
// to the patch's rim, the cells next to the contact that the rim does not touch, in equal shares.
// Excavation (excavate): a volume taken evenly from the contact cells and dropped behind the wheel.
// Repose (relax): neighbours (x then y, in raster order) whose heights differ by more than
// cell_m·tan(repose angle) move soil from the higher to the lower until they differ by exactly that
// — Gauss–Seidel passes within a window —, but not into or out of the cells held: those the wheel
// that is yielding covers, so soil cannot slide into the space under it, nor from under its rim.
// (The other wheels' cells are not held: where the window reaches a trailing wheel's front, the
// repose may slide soil there.) Every loop runs in a fixed order: bit-for-bit repeatable.
//
// Bookkeeping: cut_m3 counts every volume taken from a cell, fill_m3 every volume added, so
//   Σ(surface − initial surface)·cell² = fill − cut,   cut − fill = compacted_m3,
// the sum over the cells in the window and those it left behind (shift).
//
// Window (shift): the grid covers a window of the ground that can move by whole cells, so that it
// follows a rover across ground larger than itself. Cells the window keeps keep their state; cells
// it takes in start undisturbed at the initial surface; cells it leaves behind are forgotten but
// for their share of the earthwork, the compacted area, the deepest cut and the largest sinkage
// excess (their ruts do not come back when the window returns over them).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "sim/soil/soil_params.hpp"
#include "sim/soil/vec3.hpp"

namespace marsokhod::sim::soil {

struct GridSpec {
  double origin_x_m = -1.0;  // the corner of cell (0, 0)
  double origin_y_m = -1.0;
  double cell_m = 0.02;
  int cells_x = 100;
  int cells_y = 100;
};

// Throws std::invalid_argument naming the field (cell 1 mm – 10 cm, 2 – 4096 cells a side).
void validate(const GridSpec& spec);

// The ground's change from its initial surface, as earthworks count it: cut_m3 = Σ max(0,
// initial − surface)·cell², fill_m3 = Σ max(0, surface − initial)·cell². Unlike SoilVolumes'
// books it does not count soil moved back and forth (a bank pushed up and slid back).
struct Earthwork {
  double cut_m3 = 0.0;
  double fill_m3 = 0.0;
};

struct SoilVolumes {
  double cut_m3 = 0.0;        // soil taken from cells (pressed, excavated, slid off a slope)
  double fill_m3 = 0.0;       // soil added to cells
  double compacted_m3 = 0.0;  // soil compacted in place (the volume the grid lost)
  double excavated_m3 = 0.0;  // the part of cut_m3 the blades carried behind a wheel
  double relaxed_m3 = 0.0;    // the part of cut_m3 that slid down to the angle of repose
};

// A rigid cylinder seen by the grid: its centre, unit axle, radius and width.
struct Cylinder {
  Vec3 center_m{};
  Vec3 axle{0.0, 1.0, 0.0};
  double radius_m = 0.115;
  double width_m = 0.15;
};

// A box of cells, inclusive; empty when max < min.
struct CellBox {
  int min_x = 0, min_y = 0, max_x = -1, max_y = -1;
  bool empty() const { return max_x < min_x || max_y < min_y; }
  // The box grown by n cells each way (empty stays empty; the grid clips it where used).
  CellBox grown(int n) const {
    if (empty()) return *this;
    return {min_x - n, min_y - n, max_x + n, max_y + n};
  }
  // The smallest box holding both (either may be empty).
  CellBox united(const CellBox& other) const {
    if (other.empty()) return *this;
    if (empty()) return other;
    return {std::min(min_x, other.min_x), std::min(min_y, other.min_y),
            std::max(max_x, other.max_x), std::max(max_y, other.max_y)};
  }
};

// The cells a press touched, for excavation and relaxation to act on.
struct Footprint {
  std::vector<int> contact_cells;                    // cell indices, ascending
  int min_x = 0, min_y = 0, max_x = -1, max_y = -1;  // their box (empty: max < min)
  // The cells under the part of the wheel that reaches down near the soil (the contact cells and
  // those under the rim's arc just clear of it), ascending.
  std::vector<int> covered_cells;
  CellBox box() const { return {min_x, min_y, max_x, max_y}; }
};

class SoilGrid {
 public:
  // The surface starts at initial_surface_m(x, y) at each cell's centre. Throws
  // std::invalid_argument for a bad spec or soil, or a non-finite initial surface.
  SoilGrid(GridSpec spec, SoilParams soil,
           const std::function<double(double, double)>& initial_surface_m);

  const GridSpec& spec() const { return spec_; }
  // Bilinear between cell centres; beyond the grid the nearest edge cell's value. (Inline: the
  // contacts sample the surface many times a step.)
  double surface_m(double x_m, double y_m) const { return bilinear(surface_, nullptr, x_m, y_m); }
  double undisturbed_m(double x_m, double y_m) const {
    return bilinear(surface_, &sinkage_, x_m, y_m);
  }
  double plastic_sinkage_m(double x_m, double y_m) const;
  // How far above the soil a rim may be and still touch it: the elastic rebound of the plastic
  // sinkage, sinkage_m / unloading_stiffness_ratio, or 0.1 mm.
  double touch_tolerance_m(double x_m, double y_m) const;
  // The undisturbed surface's upward unit normal, from central differences span_m apart.
  Vec3 normal(double x_m, double y_m, double span_m) const;

  double cell_surface_m(int ix, int iy) const { return surface_[index(ix, iy)]; }
  // Every cell's surface, row by row (cell (ix, iy) at iy·cells_x + ix): what surface_m
  // interpolates, for a four-wide form of it (wide.hpp).
  const double* cell_surfaces_m() const { return surface_.data(); }
  double cell_sinkage_m(int ix, int iy) const { return sinkage_[index(ix, iy)]; }
  double cell_compaction_m(int ix, int iy) const { return compaction_[index(ix, iy)]; }
  double cell_loose_m(int ix, int iy) const { return loose_[index(ix, iy)]; }
  double cell_initial_m(int ix, int iy) const { return initial_[index(ix, iy)]; }
  void set_cell_surface_m(int ix, int iy, double level_m);  // for tests and scenario set-up
  // Raked level: every cell back at its initial surface, no sinkage or compaction, the books at 0
  // (the ground the window left behind with them).
  void level();
  // Moves the window dx_cells along x and dy_cells along y (its origin by whole cells): see the
  // header comment. Every cell counts as changed. Throws std::invalid_argument when the initial
  // surface is not finite on a cell taken in.
  void shift(int dx_cells, int dy_cells);
  const SoilVolumes& volumes() const { return volumes_; }
  // The deepest a cell's surface lies below its initial level among the cells whose centres fall
  // inside [x0, x1] × [y0, y1] (a rut's or a trench's depth, vertical); 0 where none lies lower
  // or no centre falls inside.
  double max_depth_m(double x0_m, double y0_m, double x1_m, double y1_m) const;
  // The same over the whole window and the ground it left behind.
  double deepest_m() const;
  // The most any cell's plastic sinkage has exceeded its depth below its initial surface since
  // construction or level(): sinkage_m − max(0, initial − surface), taken whenever soil is laid
  // on a cell or a press cuts it. A press of unpressed ground leaves it at 0 (its cut adds as
  // much to both), and so does soil laid in a rut (it takes from the sinkage what it adds to the
  // surface); a bank that a wheel then presses, whose undisturbed level is its top, raises it by
  // the height pressed, at most the bank's (0.7–4 cm in the shipped sand scenarios on unit 1,
  // most where turns in place press the banks they pushed up). (Before loose soil was kept apart,
  // 2026-12-01, soil sliding back into a rut raised that level as if it were pressed ground,
  // without bound: 5–14 cm in the shipped sand scenarios, docs/simulator.md.)
  double max_sinkage_excess_m() const { return max_sinkage_excess_m_; }
  // The area of the cells compacted in place (compaction_m > 0), in the window and left behind:
  // compacted_m3 over it is the mean compaction of the ground the wheels pressed.
  double compacted_area_m2() const;
  // In the window and left behind.
  Earthwork earthwork() const;
  // The box of the cells whose surface may have changed since the last clear_changed() (all of
  // them after construction or level()): what a copy of the surface (the physics' height field)
  // has to take again.
  const CellBox& changed() const { return changed_; }
  void clear_changed() { changed_ = CellBox{}; }

  // Cuts the cells under the cylinder down to its rim; returns the contact patch (the second form
  // fills `footprint`, keeping its list's capacity from step to step).
  Footprint press(const Cylinder& wheel);
  void press(const Cylinder& wheel, Footprint& footprint);
  // Takes volume_m3 evenly from the footprint's contact cells and drops it on the cells
  // behind_m behind the centre (along −toward, horizontal), across the wheel's width.
  // Returns the box of the cells the soil landed on (empty when none did).
  CellBox excavate(const Footprint& footprint, const Cylinder& wheel, const Vec3& toward,
                   double behind_m, double volume_m3);
  // Relaxes slopes steeper than the angle of repose in the footprint's box (or a box) grown by
  // margin cells.
  void relax(const Footprint& footprint, int margin_cells, int passes);
  // With `held`, no soil moves into or out of its covered cells: soil cannot slide into the space
  // under a wheel, nor out from under its rim.
  void relax(const CellBox& box, int margin_cells, int passes, const Footprint* held = nullptr);

 private:
  std::size_t index(int ix, int iy) const {
    return static_cast<std::size_t>(iy) * static_cast<std::size_t>(spec_.cells_x) +
           static_cast<std::size_t>(ix);
  }
  double cell_x_m(int ix) const { return spec_.origin_x_m + (ix + 0.5) * spec_.cell_m; }
  double cell_y_m(int iy) const { return spec_.origin_y_m + (iy + 0.5) * spec_.cell_m; }
  double bilinear(const std::vector<double>& field, const std::vector<double>* added, double x_m,
                  double y_m, const std::vector<double>* taken = nullptr) const;
  void spread(const std::vector<int>& cells, double volume_m3);
  void collect_rim(const Footprint& footprint, int box_x, int box_y, int width, int words);
  void relax_box(const CellBox& box, int margin_cells, int passes);
  bool relax_pair(std::size_t first, std::size_t second, double limit_m) {
    if ((held_[first] | held_[second]) != 0) return false;
    const double difference = surface_[first] - surface_[second];
    if (std::abs(difference) <= limit_m) return false;
    move_downhill(first, second, difference, limit_m);
    return true;
  }
  void move_downhill(std::size_t first, std::size_t second, double difference, double limit_m);
  // Lays h of loose soil on cell i: as much of it as fills the cell's rut (its plastic sinkage)
  // is loose soil in the rut, which takes that much from the sinkage, so the undisturbed level
  // (surface + sinkage) stays where the rut was pressed from; the rest raises that level as a
  // pile on undisturbed ground.
  void lay(std::size_t i, double h) {
    surface_[i] += h;
    const double filled = std::min(sinkage_[i], h);
    sinkage_[i] -= filled;
    loose_[i] += filled;
    above_[i] += h - filled;
    note_excess(i);
  }
  // After soil was laid on cell i or a press cut it: the largest sinkage excess so far.
  void note_excess(std::size_t i) {
    const double excess = sinkage_[i] - std::max(0.0, initial_[i] - surface_[i]);
    max_sinkage_excess_m_ = std::max(max_sinkage_excess_m_, excess);
  }
  // Takes h from the top of cell i: soil laid above its undisturbed level first (which lowers
  // that level with it), then its rut's loose soil, which gives its depth back to the sinkage,
  // then the ground.
  void take(std::size_t i, double h) {
    surface_[i] -= h;
    const double from_above = std::min(above_[i], h);
    above_[i] -= from_above;
    const double back = std::min(loose_[i], h - from_above);
    sinkage_[i] += back;
    loose_[i] -= back;
  }
  void mark_changed(int min_x, int min_y, int max_x, int max_y);
  void mark_changed_cell(std::size_t cell);

  // The initial surface at cell (ix, iy) of a window with that origin; throws when not finite.
  double initial_level_m(int ix, int iy, double origin_x_m, double origin_y_m) const;
  void start_cell(std::size_t i, double level_m);

  GridSpec spec_;
  SoilParams soil_;
  std::function<double(double, double)> initial_surface_m_;
  std::vector<double> surface_, sinkage_, compaction_, initial_;
  // The loose soil lying in each cell's rut (laid there after it was pressed), and the soil laid
  // on it above its undisturbed level (there the sinkage is 0), m.
  std::vector<double> loose_, above_;
  // The cells relax() may not move soil into or out of (1), else 0.
  std::vector<std::uint8_t> held_;
  // What the cells the window left behind held (shift): their earthwork, compacted area and
  // deepest cut.
  Earthwork behind_earthwork_;
  double behind_compacted_area_m2_ = 0.0;
  double behind_deepest_m_ = 0.0;
  double max_sinkage_excess_m_ = 0.0;
  // Scratch of press(): the contact cells as bits over their search box (one cell of border),
  // row-major in 64-bit words; the rim cells.
  std::vector<std::uint64_t> contact_bits_;
  std::vector<int> rim_cells_;
  double inverse_unloading_ = 0.1;  // a little above 1 / unloading_stiffness_ratio
  double repose_step_m_ = 0.0;       // the steepest difference of neighbours, cell·tan(repose)
  // (A tiny tolerance in it stops endless passes over differences rounding keeps at the limit.)
  SoilVolumes volumes_;
  CellBox changed_;
};

inline double SoilGrid::bilinear(const std::vector<double>& field,
                                 const std::vector<double>* added, double x_m, double y_m,
                                 const std::vector<double>* taken) const {
  const auto axis = [](double coordinate, int cells, int& low, int& high) {
    const double clamped = std::clamp(coordinate, 0.0, cells - 1.0);
    low = std::min(static_cast<int>(clamped), cells - 2);
    high = low + 1;
    return clamped - low;
  };
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  const double wx = axis((x_m - spec_.origin_x_m) / spec_.cell_m - 0.5, spec_.cells_x, x0, x1);
  const double wy = axis((y_m - spec_.origin_y_m) / spec_.cell_m - 0.5, spec_.cells_y, y0, y1);
  const auto at = [&](int ix, int iy) {
    const std::size_t i = index(ix, iy);
    return field[i] + (added != nullptr ? (*added)[i] : 0.0) -
           (taken != nullptr ? (*taken)[i] : 0.0);
  };
  return (1.0 - wy) * ((1.0 - wx) * at(x0, y0) + wx * at(x1, y0)) +
         wy * ((1.0 - wx) * at(x0, y1) + wx * at(x1, y1));
}

}  // namespace marsokhod::sim::soil
