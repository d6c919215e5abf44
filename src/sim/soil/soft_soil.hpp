// Soft soil under a set of wheels: the deformable grid (soil_grid.hpp) and one Wong–Reece contact
// per wheel (wheel_soil.hpp), stepped together. The interface a physics engine needs: per wheel its
// centre, axle, velocity and spin in, a force and a torque at its centre in the world frame out.
//
// Each step, in wheel order: the ground normal is the undisturbed surface's over the wheel's
// diameter; lane l's sinkage z is the depth of the rim's lowest point (centre + y_l·axle − r·up, up
// the wheel's own, nearest the normal) below the undisturbed level, along the normal — less
// unloading_stiffness_ratio times the gap where the rim has risen above the soil it pressed; its
// exit angle θ2 is the furthest angle behind the bottom (down to −θ1, searched in steps of θ1/16
// and interpolated) at which the rim is no higher above the soil than at its bottom, within the
// sagitta of a cell's diagonal on the rim (cell²/(4r), 0.87 mm: what the grid cannot resolve of a
// bowl): about −0.12 rad behind a rolling wheel, −θ1 under one that sank in place. Its front angle
// θf is found the same way ahead of the bottom (up to θ1), within the soil's elastic rebound at the
// bottom (its plastic sinkage / unloading_stiffness_ratio, the grid's contact rule) or the sagitta,
// whichever is larger: θ1 in fresh soil (the rim's point at θ1 lies in it, one look), less where
// the soil ahead lies lower, a rut the wheel rolls into. The contact gives the wrench. When the
// grid yields (below), again in wheel order: press (plastic sinkage, soil to the patch's rim),
// excavation, relaxation to the angle of repose over the patch and where the spoil landed, 3 cells
// around their box.
//
// Excavation: a blade groove of height h across the width b carries the soil it fills; rolling
// without slip it lays it down where it took it, so only the slip's share leaves the rut:
//   V = f_e · b · h · Δc · (lanes in contact / lanes),
// c the slip ∫(r_s ω − v) dt through a play of width K (c follows the slip once it has run K
// ahead of it, and stays while the slip runs back): the grooves carry soil out only as the rim
// slips on past the soil, not while it works to and fro within the soil's elastic shear. The play
// starts again when the wheel leaves the soil or its frame turns. Summed step by step, dropped one
// cell behind the rim, against the direction of motion, at the yield. (A wheel that has left the
// soil by then, its press touching no cell, takes nothing: the sum is dropped with the soil left in
// place, the books balanced.)
//
// The wheels' forces are worked out every step; the grid yields (press, excavation, repose) once
// per yield period of simulated time (10 ms unless told otherwise; 0: every step), at the wheels'
// poses of that step, with the excavation summed since the last yield. In 10 ms a wheel at the
// rover's top speed (2.8 rad/s × 0.125 m = 0.35 m/s) moves 3.5 mm, a sixth of a 2 cm cell, and the
// sinkage is measured from the undisturbed level, not from the surface the grid last left; yielding
// at every step cost 37 % of the soil's work.
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "sim/soil/soil_grid.hpp"
#include "sim/soil/wheel_soil.hpp"

namespace marsokhod::sim::soil {

class SoftSoil {
 public:
  // Throws std::invalid_argument for bad soil, grid or wheel parameters (no wheels is allowed).
  SoftSoil(SoilParams soil, GridSpec grid, const std::function<double(double, double)>& surface_m,
           const std::vector<WheelGeometry>& wheels, double yield_period_s = kYieldPeriodS);

  static constexpr double kYieldPeriodS = 0.010;

  // wheels.size() must equal the wheel count; dt_s finite and > 0. The grid yields at the end of
  // the step on which the time since its last yield reaches the period (within half a step).
  std::vector<WheelWrench> step(std::span<const WheelKinematics> wheels, double dt_s);
  // Whether the grid yielded at the end of the last step (the only steps it changes on).
  bool yielded() const { return yielded_; }

  // The lane sinkages and exit angles step() would use for one wheel, and the normal it uses.
  struct LaneContacts {
    std::vector<double> sinkage_m, exit_rad, front_rad;
  };
  LaneContacts lane_contacts(std::size_t wheel, const WheelKinematics& kinematics) const;
  Vec3 ground_normal(const WheelKinematics& kinematics, std::size_t wheel) const;

  // Raked level (SoilGrid::level), and every wheel's shear state cleared.
  void level();

  const SoilGrid& grid() const { return grid_; }
  SoilGrid& grid() { return grid_; }
  const WheelSoilContact& contact(std::size_t wheel) const { return contacts_.at(wheel); }
  std::size_t wheel_count() const { return contacts_.size(); }

 private:
  double exit_angle_rad(const Vec3& axis_point, const Vec3& forward, const Vec3& up,
                        double radius_m, double entry_rad, double lowest_m) const;
  double front_angle_rad(const Vec3& axis_point, const Vec3& forward, const Vec3& up,
                         double radius_m, double entry_rad, double lowest_m) const;
  int find_lane_contacts(std::size_t wheel, const WheelKinematics& kinematics, const Vec3& normal,
                         std::span<double> sinkage_m, std::span<double> exit_rad,
                         std::span<double> front_rad, std::span<double> entry_rad = {}) const;
  double carried_out_m3(std::size_t wheel, const WheelKinematics& kinematics, const Vec3& normal,
                        int touching_lanes, double dt_s);
  void deform(std::size_t wheel, const WheelKinematics& kinematics, double excavated_m3);

  SoilParams soil_;
  SoilGrid grid_;
  std::vector<WheelSoilContact> contacts_;
  std::vector<double> lane_sinkage_, lane_exit_, lane_front_, lane_entry_;
  double yield_period_s_;
  double since_yield_s_ = 0.0;
  bool yielded_ = false;
  std::vector<double> excavation_m3_;  // per wheel, summed since the last yield
  // Per wheel: its slip along its motion frame since it last touched or turned (slip_m), and the
  // play's output, the slip the blades have carried soil out over (carried_m ∈ [slip − K, slip]).
  struct SlipPlay {
    int direction = 1;
    double slip_m = 0.0, carried_m = 0.0;
  };
  std::vector<SlipPlay> slip_play_;
  Footprint footprint_;  // reused: its cell list keeps its capacity
};

}  // namespace marsokhod::sim::soil
