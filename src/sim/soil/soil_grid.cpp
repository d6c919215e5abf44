#include "sim/soil/soil_grid.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace marsokhod::sim::soil {
namespace {

constexpr double kMiss = std::numeric_limits<double>::infinity();
// A rim this close above a cell still touches it (no soil is pushed underneath the wheel).
constexpr double kTouchM = 1e-4;

void fail(const std::string& what) { throw std::invalid_argument("soil grid: " + what); }

// The height of a cylinder's underside above (x, y), or +∞ where the vertical line misses it; the
// cylinder's own numbers taken once for the many cells under it.
class Underside {
 public:
  explicit Underside(const Cylinder& wheel)
      : wheel_(wheel),
        horizontal_(wheel.axle[0] * wheel.axle[0] + wheel.axle[1] * wheel.axle[1]),
        radius2_(wheel.radius_m * wheel.radius_m) {}

  // Whether the vertical line through (x, y) meets the cylinder within `reach_m` of its axle.
  bool covers(double x_m, double y_m, double reach_m) const {
    double along = 0.0, across2 = 0.0;
    return project(x_m, y_m, along, across2) && across2 < reach_m * reach_m;
  }
  // +∞ also where the underside certainly lies more than a nanometre above `level_m` (no square
  // root for the cells the rim cannot reach).
  double height_above_m(double x_m, double y_m, double level_m) const {
    double along = 0.0, across2 = 0.0;
    if (!project(x_m, y_m, along, across2) || across2 >= radius2_) return kMiss;
    const double axis = wheel_.center_m[2] + along * wheel_.axle[2];
    const double clearance = axis - level_m - 1e-9;
    if (clearance > 0.0 && clearance * clearance > radius2_ - across2) return kMiss;
    return axis - std::sqrt(radius2_ - across2);
  }

 private:
  // The vertical line through (x, y): its offset along the axle's horizontal projection and its
  // squared horizontal distance from the axle's line; false where it passes beside the wheel's
  // width (or the axle stands on its end).
  bool project(double x_m, double y_m, double& along, double& across2) const {
    if (horizontal_ < 1e-12) return false;
    const double ax = wheel_.axle[0], ay = wheel_.axle[1];
    const double dx = x_m - wheel_.center_m[0], dy = y_m - wheel_.center_m[1];
    along = (dx * ax + dy * ay) / horizontal_;
    if (std::abs(along) > 0.5 * wheel_.width_m) return false;
    const double ex = dx - along * ax, ey = dy - along * ay;
    across2 = ex * ex + ey * ey;
    return true;
  }

  const Cylinder& wheel_;
  double horizontal_, radius2_;
};

}  // namespace

void validate(const GridSpec& spec) {
  std::ostringstream message;
  if (!(spec.cell_m >= 0.001 && spec.cell_m <= 0.1)) {
    message << "cell_m must be within [0.001, 0.1] m (1–2 cm suits a 0.115 m wheel), got "
            << spec.cell_m;
  } else if (spec.cells_x < 2 || spec.cells_x > 4096 || spec.cells_y < 2 || spec.cells_y > 4096) {
    message << "cells_x and cells_y must be within [2, 4096], got " << spec.cells_x << " and "
            << spec.cells_y;
  } else if (!std::isfinite(spec.origin_x_m) || !std::isfinite(spec.origin_y_m)) {
    message << "origin_x_m and origin_y_m must be finite, got " << spec.origin_x_m << " and "
            << spec.origin_y_m;
  } else {
    return;
  }
  fail(message.str());
}

SoilGrid::SoilGrid(GridSpec spec, SoilParams soil,
                   const std::function<double(double, double)>& initial_surface_m)
    : spec_(spec), soil_(std::move(soil)), initial_surface_m_(initial_surface_m) {
  validate(spec_);
  validate(soil_);
  const std::size_t count = static_cast<std::size_t>(spec_.cells_x) * spec_.cells_y;
  surface_.resize(count);
  initial_.resize(count);
  sinkage_.resize(count);
  compaction_.resize(count);
  loose_.resize(count);
  above_.resize(count);
  held_.assign(count, 0);
  for (int iy = 0; iy < spec_.cells_y; ++iy) {
    for (int ix = 0; ix < spec_.cells_x; ++ix) {
      start_cell(index(ix, iy), initial_level_m(ix, iy, spec_.origin_x_m, spec_.origin_y_m));
    }
  }
  mark_changed(0, 0, spec_.cells_x - 1, spec_.cells_y - 1);
  repose_step_m_ = spec_.cell_m * std::tan(soil_.repose_angle_rad) + 1e-12;
  inverse_unloading_ = (1.0 + 1e-12) / soil_.unloading_stiffness_ratio;  // a bound, not a value
}

double SoilGrid::initial_level_m(int ix, int iy, double origin_x_m, double origin_y_m) const {
  const double level = initial_surface_m_(origin_x_m + (ix + 0.5) * spec_.cell_m,
                                          origin_y_m + (iy + 0.5) * spec_.cell_m);
  if (!std::isfinite(level)) {
    std::ostringstream message;
    message << "the initial surface at cell (" << ix << ", " << iy << ") is " << level
            << "; it must be a finite height in metres";
    fail(message.str());
  }
  return level;
}

// Cell i = (ix, iy) undisturbed at `level`.
void SoilGrid::start_cell(std::size_t i, double level) {
  surface_[i] = level;
  initial_[i] = level;
  sinkage_[i] = 0.0;
  compaction_[i] = 0.0;
  loose_[i] = 0.0;
  above_[i] = 0.0;
}

// The levels of the cells taken in come first (a surface that is not finite there leaves the
// window as it was). Cells the window keeps move to their new indices in a pass whose direction
// reads every source before it is overwritten (rows and columns ascending when the window moves
// up, descending when it moves down); the others are counted into the books left behind before
// they are overwritten.
void SoilGrid::shift(int dx_cells, int dy_cells) {
  if (dx_cells == 0 && dy_cells == 0) return;
  const int nx = spec_.cells_x, ny = spec_.cells_y;
  const double area = spec_.cell_m * spec_.cell_m;
  const auto taken_in = [&](int ix, int iy) {  // a cell of the new window the old one lacks
    const int from_x = ix + dx_cells, from_y = iy + dy_cells;
    return from_x < 0 || from_x >= nx || from_y < 0 || from_y >= ny;
  };
  const double origin_x = spec_.origin_x_m + dx_cells * spec_.cell_m;
  const double origin_y = spec_.origin_y_m + dy_cells * spec_.cell_m;
  std::vector<double> levels;  // of the cells taken in, in raster order
  for (int iy = 0; iy < ny; ++iy) {
    for (int ix = 0; ix < nx; ++ix) {
      if (taken_in(ix, iy)) levels.push_back(initial_level_m(ix, iy, origin_x, origin_y));
    }
  }
  const auto kept = [&](int ix, int iy) {  // a cell of the old window the new one keeps
    return ix - dx_cells >= 0 && ix - dx_cells < nx && iy - dy_cells >= 0 && iy - dy_cells < ny;
  };
  for (int iy = 0; iy < ny; ++iy) {
    for (int ix = 0; ix < nx; ++ix) {
      if (kept(ix, iy)) continue;
      const std::size_t i = index(ix, iy);
      const double change = surface_[i] - initial_[i];
      (change < 0.0 ? behind_earthwork_.cut_m3 : behind_earthwork_.fill_m3) +=
          std::abs(change) * area;
      if (compaction_[i] > 0.0) behind_compacted_area_m2_ += area;
      behind_deepest_m_ = std::max(behind_deepest_m_, -change);
    }
  }
  spec_.origin_x_m = origin_x;
  spec_.origin_y_m = origin_y;
  const bool up_y = dy_cells >= 0, up_x = dx_cells >= 0;
  for (int row = 0; row < ny; ++row) {
    const int iy = up_y ? row : ny - 1 - row;
    for (int column = 0; column < nx; ++column) {
      const int ix = up_x ? column : nx - 1 - column;
      const std::size_t i = index(ix, iy);
      const int from_x = ix + dx_cells, from_y = iy + dy_cells;
      if (from_x >= 0 && from_x < nx && from_y >= 0 && from_y < ny) {
        const std::size_t from = index(from_x, from_y);
        surface_[i] = surface_[from];
        initial_[i] = initial_[from];
        sinkage_[i] = sinkage_[from];
        compaction_[i] = compaction_[from];
        loose_[i] = loose_[from];
        above_[i] = above_[from];
      }
    }
  }
  std::size_t next = 0;
  for (int iy = 0; iy < ny; ++iy) {
    for (int ix = 0; ix < nx; ++ix) {
      if (taken_in(ix, iy)) start_cell(index(ix, iy), levels[next++]);
    }
  }
  mark_changed(0, 0, nx - 1, ny - 1);
}

double SoilGrid::plastic_sinkage_m(double x_m, double y_m) const {
  return bilinear(sinkage_, nullptr, x_m, y_m);
}

double SoilGrid::touch_tolerance_m(double x_m, double y_m) const {
  return std::max(kTouchM, plastic_sinkage_m(x_m, y_m) / soil_.unloading_stiffness_ratio);
}

Vec3 SoilGrid::normal(double x_m, double y_m, double span_m) const {
  const double h = 0.5 * std::max(span_m, spec_.cell_m);
  // The ground's level, without the loose soil piled above it: the banks a wheel pushed up beside
  // its rut do not tilt its frame.
  const auto level = [&](double x, double y) {
    return bilinear(surface_, &sinkage_, x, y, &above_);
  };
  const double slope_x = (level(x_m + h, y_m) - level(x_m - h, y_m)) / (2.0 * h);
  const double slope_y = (level(x_m, y_m + h) - level(x_m, y_m - h)) / (2.0 * h);
  const Vec3 up{-slope_x, -slope_y, 1.0};
  return (1.0 / norm(up)) * up;
}

void SoilGrid::set_cell_surface_m(int ix, int iy, double level_m) {
  if (ix < 0 || iy < 0 || ix >= spec_.cells_x || iy >= spec_.cells_y || !std::isfinite(level_m)) {
    fail("set_cell_surface_m: the cell must lie in the grid and the level be finite");
  }
  surface_[index(ix, iy)] = level_m;
  initial_[index(ix, iy)] = level_m;
  mark_changed(ix, iy, ix, iy);
}

void SoilGrid::mark_changed(int min_x, int min_y, int max_x, int max_y) {
  if (max_x < min_x || max_y < min_y) return;
  if (changed_.empty()) {
    changed_ = {min_x, min_y, max_x, max_y};
    return;
  }
  changed_.min_x = std::min(changed_.min_x, min_x);
  changed_.min_y = std::min(changed_.min_y, min_y);
  changed_.max_x = std::max(changed_.max_x, max_x);
  changed_.max_y = std::max(changed_.max_y, max_y);
}

void SoilGrid::mark_changed_cell(std::size_t cell) {
  const auto columns = static_cast<std::size_t>(spec_.cells_x);
  const int ix = static_cast<int>(cell % columns), iy = static_cast<int>(cell / columns);
  mark_changed(ix, iy, ix, iy);
}

void SoilGrid::spread(const std::vector<int>& cells, double volume_m3) {
  const double depth =
      volume_m3 / (static_cast<double>(cells.size()) * spec_.cell_m * spec_.cell_m);
  for (int cell : cells) {
    lay(static_cast<std::size_t>(cell), depth);
    mark_changed_cell(static_cast<std::size_t>(cell));
  }
  volumes_.fill_m3 += volume_m3;
}

void SoilGrid::level() {
  surface_ = initial_;
  std::fill(sinkage_.begin(), sinkage_.end(), 0.0);
  std::fill(compaction_.begin(), compaction_.end(), 0.0);
  std::fill(loose_.begin(), loose_.end(), 0.0);
  std::fill(above_.begin(), above_.end(), 0.0);
  volumes_ = SoilVolumes{};
  behind_earthwork_ = Earthwork{};
  behind_compacted_area_m2_ = 0.0;
  behind_deepest_m_ = 0.0;
  max_sinkage_excess_m_ = 0.0;
  mark_changed(0, 0, spec_.cells_x - 1, spec_.cells_y - 1);
}

double SoilGrid::max_depth_m(double x0_m, double y0_m, double x1_m, double y1_m) const {
  // Cell i's centre lies in [a, b] for ceil((a − o)/cell − 0.5) ≤ i ≤ floor((b − o)/cell − 0.5).
  const auto range = [this](double low_m, double high_m, double origin_m, int cells) {
    const double c = spec_.cell_m;
    const double first = std::ceil((low_m - origin_m) / c - 0.5);
    const double last = std::floor((high_m - origin_m) / c - 0.5);
    return std::pair{static_cast<int>(std::clamp(first, 0.0, static_cast<double>(cells))),
                     static_cast<int>(std::clamp(last, -1.0, cells - 1.0))};
  };
  const auto [x_first, x_last] = range(x0_m, x1_m, spec_.origin_x_m, spec_.cells_x);
  const auto [y_first, y_last] = range(y0_m, y1_m, spec_.origin_y_m, spec_.cells_y);
  double depth = 0.0;
  for (int iy = y_first; iy <= y_last; ++iy) {
    for (int ix = x_first; ix <= x_last; ++ix) {
      const std::size_t i = index(ix, iy);
      depth = std::max(depth, initial_[i] - surface_[i]);
    }
  }
  return depth;
}

double SoilGrid::deepest_m() const {
  double depth = behind_deepest_m_;
  for (std::size_t i = 0; i < surface_.size(); ++i) {
    depth = std::max(depth, initial_[i] - surface_[i]);
  }
  return depth;
}

double SoilGrid::compacted_area_m2() const {
  const auto cells = std::count_if(compaction_.begin(), compaction_.end(),
                                   [](double compaction_m) { return compaction_m > 0.0; });
  return static_cast<double>(cells) * spec_.cell_m * spec_.cell_m + behind_compacted_area_m2_;
}

Earthwork SoilGrid::earthwork() const {
  Earthwork e = behind_earthwork_;
  const double area = spec_.cell_m * spec_.cell_m;
  for (std::size_t i = 0; i < surface_.size(); ++i) {
    const double change = surface_[i] - initial_[i];
    (change < 0.0 ? e.cut_m3 : e.fill_m3) += std::abs(change) * area;
  }
  return e;
}

Footprint SoilGrid::press(const Cylinder& wheel) {
  Footprint footprint;
  press(wheel, footprint);
  return footprint;
}

void SoilGrid::press(const Cylinder& wheel, Footprint& footprint) {
  footprint.contact_cells.clear();
  footprint.covered_cells.clear();
  const auto cell_of = [&](double coordinate, double origin, int cells) {
    return std::clamp(static_cast<int>(std::floor((coordinate - origin) / spec_.cell_m)), 0,
                      cells - 1);
  };
  // The shadow of the part of the cylinder within `radius` of its axle: half its width along the
  // axle, the radius across.
  int min_x = 0, max_x = 0, min_y = 0, max_y = 0;
  const auto shadow = [&](double radius) {
    const auto reach = [&](double axle_component) {
      return std::abs(axle_component) * 0.5 * wheel.width_m +
             radius * std::sqrt(std::max(1.0 - axle_component * axle_component, 0.0));
    };
    const double reach_x = reach(wheel.axle[0]), reach_y = reach(wheel.axle[1]);
    min_x = cell_of(wheel.center_m[0] - reach_x, spec_.origin_x_m, spec_.cells_x);
    max_x = cell_of(wheel.center_m[0] + reach_x, spec_.origin_x_m, spec_.cells_x);
    min_y = cell_of(wheel.center_m[1] - reach_y, spec_.origin_y_m, spec_.cells_y);
    max_y = cell_of(wheel.center_m[1] + reach_y, spec_.origin_y_m, spec_.cells_y);
  };
  shadow(wheel.radius_m);
  // Only the rim below the highest level a cell of the shadow still touches at can touch a cell:
  // where the rim is g above that level the contact lies within √(r² − g²) of the axle (with a
  // nanometre to spare for rounding; every cell inside is then tested exactly).
  double top = -std::numeric_limits<double>::infinity();
  for (int iy = min_y; iy <= max_y; ++iy) {
    for (int ix = min_x; ix <= max_x; ++ix) {
      const std::size_t i = index(ix, iy);
      top = std::max(top, surface_[i] + std::max(kTouchM, sinkage_[i] * inverse_unloading_));
    }
  }
  const double gap = wheel.center_m[2] - std::abs(wheel.axle[2]) * 0.5 * wheel.width_m - top -
                     1e-9;
  double reach = wheel.radius_m;
  if (gap > 0.0) {
    reach = std::sqrt(std::max(wheel.radius_m * wheel.radius_m - gap * gap, 0.0)) + 1e-9;
    shadow(reach);
  }
  const int box_x = min_x - 1, box_y = min_y - 1;  // the contact bit map's corner
  const int width = max_x - min_x + 3, height = max_y - min_y + 3;
  const int words = (width + 63) / 64;
  contact_bits_.assign(static_cast<std::size_t>(words * height), 0);
  int contact_min_x = max_x + 1, contact_max_x = min_x - 1;
  int contact_min_y = max_y + 1, contact_max_y = min_y - 1;
  const double area = spec_.cell_m * spec_.cell_m;
  double displaced_m3 = 0.0;
  bool cut_any = false;
  const Underside underside(wheel);
  // Raster order: the contact cells come out ascending.
  for (int iy = min_y; iy <= max_y; ++iy) {
    for (int ix = min_x; ix <= max_x; ++ix) {
      const std::size_t i = index(ix, iy);
      if (underside.covers(cell_x_m(ix), cell_y_m(iy), reach)) {
        footprint.covered_cells.push_back(static_cast<int>(i));
      }
      // A rim above the highest level at which this cell still carries it is a miss as before.
      const double rim = underside.height_above_m(
          cell_x_m(ix), cell_y_m(iy),
          surface_[i] + std::max(kTouchM, sinkage_[i] * inverse_unloading_));
      // Within the elastic rebound of its plastic sinkage the cell still carries the rim
      // (surface + max(a, b) > rim exactly when both sums are: the rebound only when needed).
      if (rim > surface_[i] + kTouchM &&
          rim > surface_[i] + sinkage_[i] / soil_.unloading_stiffness_ratio) {
        continue;
      }
      footprint.contact_cells.push_back(static_cast<int>(i));
      const int column = ix - box_x;
      contact_bits_[static_cast<std::size_t>((iy - box_y) * words + column / 64)] |=
          std::uint64_t{1} << (column % 64);
      contact_min_x = std::min(contact_min_x, ix);
      contact_max_x = std::max(contact_max_x, ix);
      contact_min_y = std::min(contact_min_y, iy);
      contact_max_y = std::max(contact_max_y, iy);
      if (rim >= surface_[i]) continue;
      const double cut = surface_[i] - rim;
      surface_[i] = rim;
      cut_any = true;
      sinkage_[i] += cut;
      // Pressed, the loose soil becomes ground: in a rut as deep as the cut; all of it where soil
      // lay above the undisturbed level, which the press then starts from.
      loose_[i] = above_[i] > 0.0 ? 0.0 : loose_[i] - std::min(loose_[i], cut);
      above_[i] = 0.0;
      note_excess(i);
      compaction_[i] += (1.0 - soil_.displaced_fraction) * cut;
      volumes_.cut_m3 += cut * area;
      volumes_.compacted_m3 += (1.0 - soil_.displaced_fraction) * cut * area;
      displaced_m3 += soil_.displaced_fraction * cut * area;
    }
  }
  if (cut_any) mark_changed(contact_min_x, contact_min_y, contact_max_x, contact_max_y);
  footprint.min_x = contact_min_x;
  footprint.max_x = contact_max_x;
  footprint.min_y = contact_min_y;
  footprint.max_y = contact_max_y;
  if (footprint.contact_cells.empty()) {
    footprint.max_x = footprint.min_x - 1;
    footprint.max_y = footprint.min_y - 1;
  }
  collect_rim(footprint, box_x, box_y, width, words);
  if (displaced_m3 > 0.0) {
    if (rim_cells_.empty()) {  // nowhere to go (the grid's edge): compacted after all
      volumes_.compacted_m3 += displaced_m3;
    } else {
      spread(rim_cells_, displaced_m3);
    }
  }
}

// The patch's rim: the 8-neighbours of contact cells that the wheel does not touch, within the
// grid, in raster order (ascending). The contact bit map, dilated by one cell each way, less the
// contact itself.
void SoilGrid::collect_rim(const Footprint& footprint, int box_x, int box_y, int width,
                           int words) {
  rim_cells_.clear();
  if (footprint.contact_cells.empty()) return;
  const auto bits = [&](int row, int word) -> std::uint64_t {
    if (row < 0 || word < 0 || word >= words ||
        static_cast<std::size_t>(row * words) >= contact_bits_.size()) {
      return 0;
    }
    return contact_bits_[static_cast<std::size_t>(row * words + word)];
  };
  const int rows = static_cast<int>(contact_bits_.size()) / words;
  for (int row = std::max(footprint.min_y - 1 - box_y, 0);
       row <= std::min(footprint.max_y + 1 - box_y, rows - 1); ++row) {
    const int iy = box_y + row;
    if (iy < 0 || iy >= spec_.cells_y) continue;
    for (int word = 0; word < words; ++word) {
      const auto column = [&](int w) { return bits(row - 1, w) | bits(row, w) | bits(row + 1, w); };
      const std::uint64_t middle = column(word);
      std::uint64_t dilated = middle | (middle << 1) | (middle >> 1) | (column(word - 1) >> 63) |
                              (column(word + 1) << 63);
      dilated &= ~bits(row, word);
      const int used = std::min(64, width - 64 * word);
      if (used < 64) dilated &= (std::uint64_t{1} << used) - 1;
      while (dilated != 0) {
        const int bit = std::countr_zero(dilated);
        dilated &= dilated - 1;
        const int ix = box_x + 64 * word + bit;
        if (ix < 0 || ix >= spec_.cells_x) continue;
        rim_cells_.push_back(static_cast<int>(index(ix, iy)));
      }
    }
  }
}

CellBox SoilGrid::excavate(const Footprint& footprint, const Cylinder& wheel, const Vec3& toward,
                           double behind_m, double volume_m3) {
  if (footprint.contact_cells.empty() || !(volume_m3 > 0.0)) return {};
  const double tx = toward[0], ty = toward[1];
  const double length = std::hypot(tx, ty);
  const double ax = wheel.axle[0], ay = wheel.axle[1];
  const double axle_length = std::hypot(ax, ay);
  if (length < 1e-9 || axle_length < 1e-9) return {};
  const int lanes = std::max(1, static_cast<int>(std::lround(wheel.width_m / spec_.cell_m)));
  std::vector<int> targets;
  for (int lane = 0; lane < lanes; ++lane) {
    const double offset = ((lane + 0.5) / lanes - 0.5) * wheel.width_m;
    const double x = wheel.center_m[0] - behind_m * tx / length + offset * ax / axle_length;
    const double y = wheel.center_m[1] - behind_m * ty / length + offset * ay / axle_length;
    const double fx = std::floor((x - spec_.origin_x_m) / spec_.cell_m);
    const double fy = std::floor((y - spec_.origin_y_m) / spec_.cell_m);
    if (fx < 0.0 || fy < 0.0 || fx >= spec_.cells_x || fy >= spec_.cells_y) continue;
    targets.push_back(static_cast<int>(index(static_cast<int>(fx), static_cast<int>(fy))));
  }
  std::sort(targets.begin(), targets.end());
  targets.erase(std::unique(targets.begin(), targets.end()), targets.end());
  if (targets.empty()) return {};  // it would land off the grid: keep the soil where it is
  const double depth = volume_m3 / (static_cast<double>(footprint.contact_cells.size()) *
                                    spec_.cell_m * spec_.cell_m);
  for (int cell : footprint.contact_cells) take(static_cast<std::size_t>(cell), depth);
  mark_changed(footprint.min_x, footprint.min_y, footprint.max_x, footprint.max_y);
  volumes_.cut_m3 += volume_m3;
  volumes_.excavated_m3 += volume_m3;
  spread(targets, volume_m3);
  const auto columns = static_cast<std::size_t>(spec_.cells_x);
  CellBox landed{spec_.cells_x, spec_.cells_y, -1, -1};
  for (int cell : targets) {
    const int ix = static_cast<int>(static_cast<std::size_t>(cell) % columns);
    const int iy = static_cast<int>(static_cast<std::size_t>(cell) / columns);
    landed = {std::min(landed.min_x, ix), std::min(landed.min_y, iy), std::max(landed.max_x, ix),
              std::max(landed.max_y, iy)};
  }
  return landed;
}

void SoilGrid::move_downhill(std::size_t first, std::size_t second, double difference,
                             double limit_m) {
  const double moved = 0.5 * (std::abs(difference) - limit_m);
  const std::size_t higher = difference > 0.0 ? first : second;
  const std::size_t lower = difference > 0.0 ? second : first;
  take(higher, moved);
  lay(lower, moved);
  const double volume = moved * spec_.cell_m * spec_.cell_m;
  volumes_.cut_m3 += volume;
  volumes_.fill_m3 += volume;
  volumes_.relaxed_m3 += volume;
}

void SoilGrid::relax(const Footprint& footprint, int margin_cells, int passes) {
  relax(footprint.box(), margin_cells, passes);
}

void SoilGrid::relax(const CellBox& box, int margin_cells, int passes, const Footprint* held) {
  if (box.empty()) return;
  if (held != nullptr) {
    for (int cell : held->covered_cells) held_[static_cast<std::size_t>(cell)] = 1;
  }
  relax_box(box, margin_cells, passes);
  if (held != nullptr) {
    for (int cell : held->covered_cells) held_[static_cast<std::size_t>(cell)] = 0;
  }
}

void SoilGrid::relax_box(const CellBox& box, int margin_cells, int passes) {
  const int x0 = std::max(box.min_x - margin_cells, 0);
  const int x1 = std::min(box.max_x + margin_cells, spec_.cells_x - 1);
  const int y0 = std::max(box.min_y - margin_cells, 0);
  const int y1 = std::min(box.max_y + margin_cells, spec_.cells_y - 1);
  const double limit = repose_step_m_;
  const auto width = static_cast<std::size_t>(spec_.cells_x);
  for (int pass = 0; pass < passes; ++pass) {
    bool moved = false;
    // In raster order, each cell with its right then its lower neighbour. A row none of whose
    // pairs is steeper than the limit (checked as it comes up, after the rows above moved soil)
    // would move nothing and is passed over.
    for (int iy = y0; iy <= y1; ++iy) {
      const std::size_t row = index(0, iy);
      const double* level = surface_.data() + row;
      double steepest = 0.0;
      for (int ix = x0; ix < x1; ++ix) {
        steepest = std::max(steepest, std::abs(level[ix] - level[ix + 1]));
      }
      if (iy < y1) {
        for (int ix = x0; ix <= x1; ++ix) {
          steepest = std::max(steepest, std::abs(level[ix] - level[ix + spec_.cells_x]));
        }
      }
      if (steepest <= limit) continue;
      for (int ix = x0; ix <= x1; ++ix) {
        const std::size_t i = row + static_cast<std::size_t>(ix);
        if (ix < x1) moved |= relax_pair(i, i + 1, limit);
        if (iy < y1) moved |= relax_pair(i, i + width, limit);
      }
    }
    if (!moved) return;
    mark_changed(x0, y0, x1, y1);
  }
}

}  // namespace marsokhod::sim::soil
