// One rigid bladed wheel in soil: the Wong–Reece stresses (wheel_stress.hpp) over a few lanes
// across its width, with a shear-displacement state instead of the slip ratio, as a force and
// torque at the wheel's centre in the world frame.
//
// Shear displacement state. Per lane and arc sample, j = (j_t, j_y): how far the blade tips have
// slid against the soil they touch, signed as the soil's pull on the wheel. Each step
//   j(u, t + dt) = j(u − Δu, t) ⊕ v_j(θ) dt,   Δu = max(ω, 0) dt / (θf − θ2),
//   v_jt = r_s ω − v_x cos θ,   v_jy = −v_y,
// u ∈ [0, 1] the position along the arc from the front θf (θ1 in fresh soil) to the exit: the rim
// carries its displacement from the entry (fresh soil, j = 0) to the exit at its own angular speed
// ω (semi-Lagrangian, stable at any step). j ⊕ dj is elastoplastic: an increment along j (or from
// j = 0) loads along Janosi–Hanamoto's curve, one against j unloads unloading_stiffness_ratio
// times stiffer than the curve's start until the mobilised share is 0, the rest loading the other
// way (Wong's repetitive shear tests unload steeply). Along the rim, soil that unloaded and is
// loaded the same way again reloads along that stiff line until it is back where it began to
// unload (the peak, kept per sample and carried with j_t), and only then follows the curve
// (SoilParams::tangential_reload_memory; unloading through 0 forgets the peak): a still wheel that
// the chassis shakes by a fraction of a millimetre keeps its grip. Where j grows monotonically
// from the entry — a driven wheel rolling steadily — this is exactly Wong–Reece's
//   j_t(θ) = r_s[(θ1 − θ) − (1 − s)(sin θ1 − sin θ)],   j_y(θ) = −v_y (θ1 − θ) / ω,
// but it needs no slip ratio: at rest Δu = 0 and j integrates the creep, so a still wheel on a
// slope is held like a spring of stiffness ≈ (c + σ tan φ)/K per unit area, and a locked wheel
// being dragged is regular.
//
// Direction: the arc's entry lies ahead of the wheel in the direction of r_s ω + v_x; when the arc
// has moved K (the soil's shear modulus) back against it, the motion frame mirrors (x → −x, the
// state mirrored along the arc and j_t negated, the blades' handedness flipped with it, the exit
// and front angles given for that step swapped). A wheel rocking in its bowl keeps its frame, and
// with it its pressure profile.
//
// Damping: over the contact's area A = Σ_lanes Δb·r·(θf − θ2), a force −R·A·v_up along the wheel's
// up (SoilParams::vertical_damping_pa_s_per_m), never pulling the wheel down into the soil beyond
// cancelling the soil's own normal force.
//
// Sidewall: moving sideways, the leading side face bulldozes soil with Rankine's passive pressure
// (sidewall_resistance_n), mobilised like the shear by the arc's mean lateral displacement.
#pragma once

#include <span>
#include <vector>

#include "sim/soil/soil_params.hpp"
#include "sim/soil/vec3.hpp"
#include "sim/soil/wheel_stress.hpp"

namespace marsokhod::sim::soil {

// The wheel as the physics engine sees it, in the world frame.
struct WheelKinematics {
  Vec3 center_m{};
  Vec3 axle{0.0, 1.0, 0.0};  // unit, toward the rover's left for every wheel
  Vec3 velocity_mps{};       // of the wheel's centre
  double spin_radps = 0.0;   // about axle; > 0 rolls the wheel along axle × ground normal
};

struct WheelDiagnostics {
  bool in_contact = false;
  double slip = 0.0;             // regularised slip (wheel_stress.hpp), sign of the wheel's frame
  double entry_angle_rad = 0.0;  // largest θ1 over the lanes
  double normal_load_n = 0.0;    // force along the ground normal
  double drawbar_pull_n = 0.0;   // force along axle × ground normal
  double lateral_n = 0.0;        // force along the axle
  double resisting_torque_nm = 0.0;  // torque about the axle (opposes a driving wheel: < 0)
  double sidewall_n = 0.0;           // the bulldozing part of lateral_n
};

struct WheelWrench {
  Vec3 force_n{};          // on the wheel, world frame
  Vec3 torque_nm{};        // about the wheel's centre, world frame
  double sinkage_m = 0.0;  // the deepest lane's
  WheelDiagnostics diagnostics;
};

class WheelSoilContact {
 public:
  // Throws std::invalid_argument (validate()) for bad soil or wheel parameters.
  WheelSoilContact(SoilParams soil, WheelGeometry wheel);

  // lane_sinkage_m: per lane (wheel.lanes, from −y to +y across the width) the depth of the rim's
  // lowest point below the undisturbed surface; ≤ 0 is no contact. lane_exit_rad: per lane the
  // exit angle θ2 ∈ [−θ1, 0] in the direction of motion (wheel_stress.hpp), or empty for 0 (a
  // rolling wheel's rut). lane_front_rad: per lane where the rim meets the soil ahead, in
  // [0, θ1], or empty for θ1 (fresh soil ahead). ground_normal: unit, up.
  WheelWrench step(const WheelKinematics& kinematics, const Vec3& ground_normal,
                   std::span<const double> lane_sinkage_m, std::span<const double> lane_exit_rad,
                   std::span<const double> lane_front_rad, double dt_s) {
    return step(kinematics, ground_normal, lane_sinkage_m, lane_exit_rad, lane_front_rad, {}, dt_s);
  }
  // lane_entry_rad (or none): each lane's θ1 as the caller took it from its sinkage,
  // std::acos(1 − clamp(s, 0, r)/r), so that the contact need not take it again.
  WheelWrench step(const WheelKinematics& kinematics, const Vec3& ground_normal,
                   std::span<const double> lane_sinkage_m, std::span<const double> lane_exit_rad,
                   std::span<const double> lane_front_rad, std::span<const double> lane_entry_rad,
                   double dt_s);
  WheelWrench step(const WheelKinematics& kinematics, const Vec3& ground_normal,
                   std::span<const double> lane_sinkage_m, std::span<const double> lane_exit_rad,
                   double dt_s) {
    return step(kinematics, ground_normal, lane_sinkage_m, lane_exit_rad, {}, dt_s);
  }
  WheelWrench step(const WheelKinematics& kinematics, const Vec3& ground_normal,
                   std::span<const double> lane_sinkage_m, double dt_s) {
    return step(kinematics, ground_normal, lane_sinkage_m, {}, {}, dt_s);
  }

  // Lateral offset of lane l's centre along the axle.
  double lane_offset_m(int lane) const;
  int direction() const { return direction_; }
  // lanes × arc samples, lane-major, in the motion frame.
  const std::vector<double>& tangential_displacement_m() const { return shear_t_; }
  const std::vector<double>& lateral_displacement_m() const { return shear_y_; }
  const SoilParams& soil() const { return soil_; }
  const WheelGeometry& wheel() const { return wheel_; }

 private:
  struct Frame;
  void update_direction(double rim_speed_mps, double travel_speed_mps, double dt_s);
  Frame motion_frame(const WheelKinematics& kinematics, const Vec3& forward_wheel,
                     double travel_mps) const;
  void advect_lane(int lane, const ContactArc& arc, double spin_radps, double travel_mps,
                   double lateral_mps, double dt_s);
  void add_lane_stresses(int lane, const ContactArc& arc, const Frame& frame,
                         WheelWrench& wrench);
  void add_damping(double contact_area_m2, const Frame& frame, const Vec3& velocity_mps,
                   WheelWrench& wrench) const;
  void add_sidewall(std::span<const double> lane_sinkage_m, const Frame& frame,
                    WheelWrench& wrench) const;

  SoilParams soil_;
  WheelGeometry wheel_;
  ShearStrength strength_;
  BladeAxes blades_;
  double modulus_pa_ = 0.0;  // k_c/b + k_φ
  double passive_ = 1.0;     // N_φ of the sidewall
  int direction_ = 1;
  double retreat_m_ = 0.0;  // how far the arc has moved back against direction_ (update_direction)
  std::vector<double> shear_t_, shear_y_, cosines_;
  // Per lane and sample, the tangential displacement at which the soil last began to unload
  // (0: none); below it the soil reloads as stiffly as it unloaded (reloaded()).
  std::vector<double> peak_t_;
  // Per arc sample of the lane being summed: sin θ, cos θ, σ, the blades' mobilised shares
  // across and along (scratch of add_lane_stresses).
  std::vector<double> sample_sin_, sample_cos_, sample_sigma_, share_across_, share_along_;
  std::vector<int> unloading_;  // the advection's unloading samples (wide::advect_loading)
};

}  // namespace marsokhod::sim::soil
