#include "sim/soil/soft_soil.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "sim/soil/angle_steps.hpp"
#include "sim/soil/wide.hpp"

namespace marsokhod::sim::soil {
namespace {

// Repose relaxation around a wheel: this many cells beyond its box, at most this many passes.
constexpr int kRelaxMarginCells = 3;
constexpr int kRelaxPasses = 4;
// Beyond the cells a wheel's spoil landed on, at least this many cells, and as many as a slope at
// the angle of repose from the pile's top down to the ground spans (at most kSpoilReachCells): a
// pile must be free to spread to its foot, or the window's edge stands as a wall around it.
constexpr int kSpoilMarginCells = 6;
constexpr int kSpoilReachCells = 40;
// The exit angle's search: steps over [−θ1, 0], and how far above its bowl a rim still touches at
// least (exit_touch_m below).
constexpr int kExitSteps = 16;
constexpr double kTouchM = 1e-4;

// How far above the soil behind its bottom a rim still touches it. The grid holds a bowl only at
// its cells' centres; between them its bilinear surface parts from the rim's circle by up to the
// sagitta of a cell's diagonal, (√2·cell)²/(8r) = cell²/(4r): 0.87 mm for 2 cm cells under the
// 0.115 m rim. A still wheel in the bowl it pressed touches it all round (θ2 = −θ1); with a
// tolerance below the sagitta (0.1 mm, before 2026-11-29) the search met the first cell's dip at
// once, the arc lay wholly ahead in whichever direction the wheel crept, and its pressure pushed
// back at each reversal: a standing centre wheel met ±0.37 of its load, a 150 Hz chatter that
// read 2.2 m/s² rms on the rover's accelerometer (docs/simulator.md).
double exit_touch_m(double cell_m, double radius_m) {
  return std::max(kTouchM, cell_m * cell_m / (4.0 * radius_m));
}

// The wheel's rolling direction along the ground (axle × normal, unit; +x of its motion frame
// before the direction it rolls in is applied).
Vec3 rolling_forward(const WheelKinematics& kinematics, const Vec3& normal) {
  const Vec3 rolling = cross(kinematics.axle, normal);
  return (1.0 / std::max(norm(rolling), 1e-12)) * rolling;
}

}  // namespace

SoftSoil::SoftSoil(SoilParams soil, GridSpec grid,
                   const std::function<double(double, double)>& surface_m,
                   const std::vector<WheelGeometry>& wheels, double yield_period_s)
    : soil_(soil), grid_(grid, soil, surface_m), yield_period_s_(yield_period_s) {
  if (!(yield_period_s >= 0.0 && yield_period_s <= 0.1)) {
    std::ostringstream message;
    message << "SoftSoil: yield_period_s must be within [0, 0.1] s (0: every step), got "
            << yield_period_s;
    throw std::invalid_argument(message.str());
  }
  contacts_.reserve(wheels.size());
  std::size_t lanes = 0;
  for (const WheelGeometry& wheel : wheels) {
    contacts_.emplace_back(soil_, wheel);
    lanes = std::max(lanes, static_cast<std::size_t>(wheel.lanes));
  }
  lane_sinkage_.resize(lanes);
  lane_exit_.resize(lanes);
  lane_front_.resize(lanes);
  lane_entry_.resize(lanes);
  excavation_m3_.assign(wheels.size(), 0.0);
  slip_play_.assign(wheels.size(), SlipPlay{});
}

void SoftSoil::level() {
  grid_.level();
  since_yield_s_ = 0.0;
  yielded_ = false;
  std::fill(excavation_m3_.begin(), excavation_m3_.end(), 0.0);
  std::fill(slip_play_.begin(), slip_play_.end(), SlipPlay{});
  for (WheelSoilContact& contact : contacts_) contact = WheelSoilContact(soil_, contact.wheel());
}

Vec3 SoftSoil::ground_normal(const WheelKinematics& kinematics, std::size_t wheel) const {
  return grid_.normal(kinematics.center_m[0], kinematics.center_m[1],
                      2.0 * contacts_.at(wheel).wheel().rim_radius_m);
}

namespace {

// Of the rim at angle θ toward `side` from its bottom: how far it lies above the soil, less
// what it lies above it at the bottom and the touch tolerance (> 0: clear of the soil).
struct RimClearance {
  const SoilGrid& grid;
  Vec3 axis_point, side, up;
  double radius_m;
  double lowest_m;  // the rim's bottom above the soil (< 0: in it)
  double bottom_m;  // max(lowest_m, 0)
  double touch_m;

  double height(double sin_theta, double cos_theta) const {
    const Vec3 rim = axis_point + (radius_m * sin_theta) * side - (radius_m * cos_theta) * up;
    return rim[2] - grid.surface_m(rim[0], rim[1]);
  }
  double operator()(double sin_theta, double cos_theta) const {
    return height(sin_theta, cos_theta) - bottom_m - touch_m;
  }
};

// Stepping out from the bottom toward clearance.side, the angle in [0, θ1] where the rim first
// rises above the soil further than it is above it at the bottom (a rim resting in its rebound
// touches its whole bowl), interpolated between the steps so that it moves continuously with the
// wheel; θ1 if it never does.
double clearing_angle_rad(const RimClearance& clearance, double entry_rad) {
  double previous_theta = 0.0;
  double previous = clearance.lowest_m - clearance.bottom_m - clearance.touch_m;  // at θ = 0
  AngleSteps angle = AngleSteps::multiples(entry_rad / kExitSteps);
  if (wide::available()) {  // four looks at a time: the same angles and clearances, to the bit
    static_assert(kExitSteps % 4 == 0);
    std::array<double, 4> sines{}, cosines{}, clearances{};
    for (int first = 1; first <= kExitSteps; first += 4) {
      for (std::size_t j = 0; j < 4; ++j, angle.advance()) {
        sines[j] = angle.sin();
        cosines[j] = angle.cos();
      }
      wide::rim_clearances(clearance.grid.spec(), clearance.grid.cell_surfaces_m(),
                           clearance.axis_point.data(), clearance.side.data(),
                           clearance.up.data(), clearance.radius_m, clearance.bottom_m,
                           clearance.touch_m, sines.data(), cosines.data(), clearances.data());
      for (int j = 0; j < 4; ++j) {
        const int k = first + j;
        const double theta = entry_rad * k / kExitSteps;
        const double current = clearances[static_cast<std::size_t>(j)];
        if (current > 0.0) {
          return previous_theta + (theta - previous_theta) * (-previous) / (current - previous);
        }
        previous_theta = theta;
        previous = current;
      }
    }
    return entry_rad;
  }
  for (int k = 1; k <= kExitSteps; ++k, angle.advance()) {
    const double theta = entry_rad * k / kExitSteps;
    const double current = clearance(angle.sin(), angle.cos());
    if (current > 0.0) {
      return previous_theta + (theta - previous_theta) * (-previous) / (current - previous);
    }
    previous_theta = theta;
    previous = current;
  }
  return entry_rad;
}

}  // namespace

// θ2: the clearing angle behind the wheel, negative. `entry_rad` is θ1 of the lane's sinkage,
// `lowest_m` how far the rim's lowest point lies above the soil (< 0: in it).
double SoftSoil::exit_angle_rad(const Vec3& axis_point, const Vec3& forward, const Vec3& up,
                                double radius_m, double entry_rad, double lowest_m) const {
  const double touch = exit_touch_m(grid_.spec().cell_m, radius_m);
  const RimClearance clearance{grid_, axis_point, -1.0 * forward, up, radius_m, lowest_m,
                               std::max(lowest_m, 0.0), touch};
  return -clearing_angle_rad(clearance, entry_rad);
}

// θf: the clearing angle ahead of the wheel. Rolling into fresh soil the rim at θ1 lies in it (θ1
// is where the undisturbed level meets the rim), and that one look settles it.
double SoftSoil::front_angle_rad(const Vec3& axis_point, const Vec3& forward, const Vec3& up,
                                 double radius_m, double entry_rad, double lowest_m) const {
  const Vec3 lowest = axis_point - radius_m * up;
  const double rebound = grid_.touch_tolerance_m(lowest[0], lowest[1]);
  const double touch = std::max(rebound, exit_touch_m(grid_.spec().cell_m, radius_m));
  const RimClearance clearance{grid_, axis_point, forward, up, radius_m, lowest_m,
                               std::max(lowest_m, 0.0), touch};
  const SinCos at_entry = sin_cos(entry_rad);
  if (clearance(at_entry.sin, at_entry.cos) <= 0.0) return entry_rad;
  return clearing_angle_rad(clearance, entry_rad);
}

// Lane sinkages and (unless their spans are empty) exit angles, front angles and the entry angles
// θ1 they were searched over (0 where a lane is not in the soil) into the spans, one per lane; the
// number of lanes in contact.
int SoftSoil::find_lane_contacts(std::size_t wheel, const WheelKinematics& kinematics,
                                 const Vec3& normal, std::span<double> sinkage_m,
                                 std::span<double> exit_rad,
                                 std::span<double> front_rad,
                                 std::span<double> entry_rad) const {
  const WheelSoilContact& contact = contacts_.at(wheel);
  std::fill(sinkage_m.begin(), sinkage_m.end(), 0.0);
  std::fill(exit_rad.begin(), exit_rad.end(), 0.0);
  std::fill(front_rad.begin(), front_rad.end(), 0.0);
  std::fill(entry_rad.begin(), entry_rad.end(), 0.0);  // θ1 = acos(1) of a lane not in the soil
  const Vec3 rolling = cross(kinematics.axle, normal);
  if (norm(rolling) < 1e-9) return 0;
  const Vec3 forward = (static_cast<double>(contact.direction()) / norm(rolling)) * rolling;
  const Vec3 up = (1.0 / norm(rolling)) * cross(rolling, kinematics.axle);
  const double radius = contact.wheel().rim_radius_m;
  int touching = 0;
  for (std::size_t lane = 0; lane < sinkage_m.size(); ++lane) {
    const Vec3 axis_point =
        kinematics.center_m + contact.lane_offset_m(static_cast<int>(lane)) * kinematics.axle;
    const Vec3 lowest = axis_point - radius * up;
    const double surface = grid_.surface_m(lowest[0], lowest[1]);
    const double undisturbed = grid_.undisturbed_m(lowest[0], lowest[1]);
    const double above = lowest[2] - surface;  // the rim's bottom above the soil
    const double gap = std::max(above, 0.0);
    const double depth =
        undisturbed - std::min(lowest[2], surface) - soil_.unloading_stiffness_ratio * gap;
    sinkage_m[lane] = depth * normal[2];
    if (sinkage_m[lane] > 0.0) {
      const double entry = std::acos(1.0 - std::min(sinkage_m[lane], radius) / radius);  // θ1
      if (!entry_rad.empty()) entry_rad[lane] = entry;
      if (!exit_rad.empty()) {
        exit_rad[lane] = exit_angle_rad(axis_point, forward, up, radius, entry, above);
      }
      if (!front_rad.empty()) {
        front_rad[lane] = front_angle_rad(axis_point, forward, up, radius, entry, above);
      }
      ++touching;
    }
  }
  return touching;
}

SoftSoil::LaneContacts SoftSoil::lane_contacts(std::size_t wheel,
                                               const WheelKinematics& kinematics) const {
  const auto lanes = static_cast<std::size_t>(contacts_.at(wheel).wheel().lanes);
  LaneContacts result{std::vector<double>(lanes, 0.0), std::vector<double>(lanes, 0.0),
                      std::vector<double>(lanes, 0.0)};
  find_lane_contacts(wheel, kinematics, ground_normal(kinematics, wheel), result.sinkage_m,
                     result.exit_rad, result.front_rad);
  return result;
}

std::vector<WheelWrench> SoftSoil::step(std::span<const WheelKinematics> wheels, double dt_s) {
  if (wheels.size() != contacts_.size() || !(dt_s > 0.0) || !std::isfinite(dt_s)) {
    std::ostringstream message;
    message << "SoftSoil::step: expected " << contacts_.size()
            << " wheels and a finite dt_s > 0, got " << wheels.size() << " and " << dt_s;
    throw std::invalid_argument(message.str());
  }
  std::vector<WheelWrench> wrenches;
  wrenches.reserve(wheels.size());
  for (std::size_t i = 0; i < wheels.size(); ++i) {
    const auto lanes = static_cast<std::size_t>(contacts_[i].wheel().lanes);
    const std::span<double> sinkage(lane_sinkage_.data(), lanes);
    const std::span<double> exit(lane_exit_.data(), lanes);
    const std::span<double> front(lane_front_.data(), lanes);
    const std::span<double> entry(lane_entry_.data(), lanes);
    const Vec3 normal = ground_normal(wheels[i], i);
    const int touching = find_lane_contacts(i, wheels[i], normal, sinkage, exit, front, entry);
    wrenches.push_back(contacts_[i].step(wheels[i], normal, sinkage, exit, front, entry, dt_s));
    const int carrying = wrenches.back().diagnostics.in_contact ? touching : 0;
    excavation_m3_[i] += carried_out_m3(i, wheels[i], normal, carrying, dt_s);
  }
  since_yield_s_ += dt_s;
  yielded_ = since_yield_s_ + 0.5 * dt_s >= yield_period_s_;
  if (yielded_) {
    for (std::size_t i = 0; i < wheels.size(); ++i) {
      deform(i, wheels[i], excavation_m3_[i]);
      excavation_m3_[i] = 0.0;
    }
    since_yield_s_ = 0.0;
  }
  return wrenches;
}

// The soil the blades carried out of the rut this step: f_e · b · h · Δc · (lanes in contact /
// lanes), c the slip r_s ω − v (v along the rolling direction) through a play of width K: the
// grooves carry soil out only as the rim slips on past the soil, not while it works to and fro
// within the soil's elastic shear (a wheel rocking in its rut carries nothing out).
double SoftSoil::carried_out_m3(std::size_t wheel, const WheelKinematics& kinematics,
                                const Vec3& normal, int touching_lanes, double dt_s) {
  const WheelGeometry& geometry = contacts_[wheel].wheel();
  SlipPlay& play = slip_play_[wheel];
  const int direction = contacts_[wheel].direction();
  if (!geometry.bladed || touching_lanes == 0 || direction != play.direction) {
    play = SlipPlay{direction, 0.0, 0.0};
    if (!geometry.bladed || touching_lanes == 0) return 0.0;
  }
  const Vec3 forward = rolling_forward(kinematics, normal);
  const double slip_speed = direction * (geometry.shear_radius_m() * kinematics.spin_radps -
                                         dot(kinematics.velocity_mps, forward));
  play.slip_m += slip_speed * dt_s;
  const double carried =
      std::clamp(play.carried_m, play.slip_m - soil_.shear_modulus_m, play.slip_m);
  const double advance = std::max(carried - play.carried_m, 0.0);
  play.carried_m = carried;
  return soil_.excavation_fraction * geometry.width_m * geometry.blade_height_m * advance *
         touching_lanes / geometry.lanes;
}

// The grid yields under the wheel as it stands: its press, then the excavation of the soil its
// blades carried since the last yield, then the repose around it.
void SoftSoil::deform(std::size_t wheel, const WheelKinematics& kinematics, double excavated_m3) {
  const WheelGeometry& geometry = contacts_[wheel].wheel();
  const Cylinder cylinder{kinematics.center_m, kinematics.axle, geometry.rim_radius_m,
                          geometry.width_m};
  grid_.press(cylinder, footprint_);
  CellBox landed;
  if (excavated_m3 > 0.0) {
    const Vec3 forward = rolling_forward(kinematics, ground_normal(kinematics, wheel));
    const double direction = contacts_[wheel].direction();
    landed = grid_.excavate(footprint_, cylinder, direction * forward,
                            geometry.rim_radius_m + grid_.spec().cell_m, excavated_m3);
  }
  // The repose over the patch and where its spoil landed, each with its margin: a short patch
  // leaves the landing row outside its own margin, and spoil never spread would stand there as a
  // wall. The cells under the rim hold still: soil neither slides from under the wheel nor into
  // the rut it stands in.
  int spoil_margin = kSpoilMarginCells;
  if (!landed.empty()) {
    double pile_m = 0.0;  // the highest landing cell above the ground's initial level
    for (int iy = landed.min_y; iy <= landed.max_y; ++iy) {
      for (int ix = landed.min_x; ix <= landed.max_x; ++ix) {
        pile_m = std::max(pile_m, grid_.cell_surface_m(ix, iy) - grid_.cell_initial_m(ix, iy));
      }
    }
    const double foot_cells = pile_m / (grid_.spec().cell_m * std::tan(soil_.repose_angle_rad));
    spoil_margin = std::clamp(static_cast<int>(std::ceil(foot_cells)) + 1, kSpoilMarginCells,
                              kSpoilReachCells);
  }
  const CellBox around =
      footprint_.box().grown(kRelaxMarginCells).united(landed.grown(spoil_margin));
  grid_.relax(around, 0, kRelaxPasses, &footprint_);
}

}  // namespace marsokhod::sim::soil
