// The rover's mechanics in MuJoCo: the center unit with the center axle, the front and rear
// levers on joints 6 and 7 (Figure 3.3: a, b, elevation α), the exterior axles on passive roll
// hinges θ within ±0.524 rad, six wheels of radius r on a 0.70 m track, on a terrain.
//
// This is the contract between the physics (sim/physics) and the rest of the simulator
// (sim/electrics, sim/firmware, sim/simulated_rover). It knows nothing of CAN or of the driver.
//
// Motors are driven by their speed–torque line at the output shaft: each step the motor delivers
//   τ_i = clamp((ω0_i − ω_i)/droop_i, −stall_i, +stall_i)
// where ω0_i is the no-load speed the electrics computed from duty cycle and supply voltage, and
// ω_i the shaft speed. A wheel's torque against its shaft's motion (a load driving the motor: it
// generates or plugs) is clamped at min(stall_i + |ω_i|/droop_i, brake_i) instead, at least
// stall_i. Wheels (0–5) turn with their shaft. A joint's shaft p̄ (6, 7) drives the joint
// through the backlash gap of Procedure 4.1; the joint drive is not back-drivable (chapter 5.3's
// lock): outside the gap's contact the joint holds its angle whatever the load.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <optional>

#include "core/params.hpp"
#include "sim/physics/terrain.hpp"

namespace marsokhod::sim {
namespace soil {
class SoftSoil;
}

// What an ideal accelerometer and gyro on the center unit read, in the sensor axes of chapter 3.3
// (x1 forward, x2 left, x3 up; equal to the robot's axes with αf = αr).
struct ImuTruth {
  // The quantity (3.5) returns: gravity minus acceleration, (0, 0, −9.81) at rest on flat ground.
  std::array<double, 3> accel_mps2{};
  double yaw_rate_radps = 0.0;  // rotation rate about x3
  // θf: roll of the front axle relative to the center axle, right-hand about x1 (left wheel up
  // is positive); the passive hinge's stops are ±0.524 rad.
  double front_tilt_rad = 0.0;
  double rear_tilt_rad = 0.0;  // θr
};

struct GroundTruth {
  std::array<double, 3> position_m{};  // center of the center axle, world frame
  // Of the center unit, R = Rz(yaw)·Ry(pitch)·Rx(roll), each by the right-hand rule about the
  // world's x, y, z: nose up is a negative pitch (−15° on a 15° uphill), left side up positive
  // roll.
  std::array<double, 3> roll_pitch_yaw_rad{};
  std::array<double, 3> velocity_mps{};  // world frame
  double yaw_rate_radps = 0.0;
  MotorVector joint_angle_rad{};  // p6, p7 of the joints themselves (wheels: wheel angle)
  // Rim speed minus ground speed along the wheel's heading: the speed at which the contact point
  // slides backwards, ω·r − v·heading for a wheel spinning about its axle; positive when the
  // wheel spins faster than it advances (driving slip), negative when it is dragged (skid).
  std::array<double, kWheelCount> wheel_slip_mps{};
  std::array<bool, kWheelCount> wheel_contact{};
  std::array<std::array<double, 3>, kWheelCount> wheel_position_m{};  // for the 3-D view
  // The passive joints, [0] front, [1] rear: the struts' pivots about the center axle
  // (strut_front, strut_rear) and the exterior axles' tilts about x (tilt_front, tilt_rear), as
  // the URDF names them (rover_urdf.hpp).
  std::array<double, 2> strut_angle_rad{};
  std::array<double, 2> axle_tilt_rad{};
};

struct MotorDrive {
  MotorVector no_load_speed_radps{};  // ω0_i at the output shaft
  MotorVector droop_radps_per_nm{};   // speed lost per N·m of load (B of (4.6))
  MotorVector stall_torque_nm{};      // the most the motor can deliver
  MotorVector brake_torque_nm{};      // a wheel's most against its shaft's motion, at speed
};

// How fast Procedure 3.4's hand turns an exterior axle.
inline constexpr double kAxleHandRateRadps = 1.0;

class RoverPhysics {
 public:
  // Builds the MuJoCo model from the geometry and the terrain. Joints start at the motor shafts'
  // initial positions (Remark 3.1), at the negative end of the backlash gap (Procedure 4.3).
  // Throws std::invalid_argument with a reason for a terrain or geometry MuJoCo cannot build.
  RoverPhysics(const Params& params, const TerrainSpec& terrain, double timestep_s = 0.001);
  ~RoverPhysics();
  RoverPhysics(const RoverPhysics&) = delete;
  RoverPhysics& operator=(const RoverPhysics&) = delete;

  void set_drive(const MotorDrive& drive);
  void step();  // advances one timestep
  double time_s() const;
  double timestep_s() const;

  MotorVector shaft_angle_rad() const;  // wheels: wheel angle; joints: p̄6, p̄7 (thesis signs)
  MotorVector shaft_velocity_radps() const;
  MotorVector shaft_torque_nm() const;  // what each motor delivered in the last step
  ImuTruth imu() const;
  GroundTruth truth() const;
  double total_mass_kg() const;

  // Faults of Field Experiment 6.2 and chapter 4: a rigid wheel, a wheel without ground contact.
  void set_wheel_blocked(std::size_t wheel, bool blocked);
  void set_wheel_contact(std::size_t wheel, bool has_contact);
  // A jammed joint (slot 0 the front, 1 the rear): the joint and its motor's shaft held where they
  // are, whatever the motor does, until released.
  void set_joint_jammed(std::size_t slot, bool jammed);

  // The calibration stand: the center unit held 1 m above the ground, all wheels free, turned by
  // R = Ry(pitch)·Rx(roll) (roll about x1 first, then pitch; right-hand rule, like GroundTruth's
  // angles). The accelerometer then reads gravity in the turned frame: roll = +π/2 puts the
  // left side (x2) up. place_on_ground() sets the rover level back on the ground beneath, its
  // joints as they are: the lowest wheel 5 mm above the ground under it, none lower.
  void place_on_stand(double roll_rad, double pitch_rad);
  void place_on_ground();
  bool on_stand() const;
  // The bench's rake: a soft soil's ground (rover_soft_soil.cpp) back to its initial level, its
  // ruts, compaction and books cleared, the wheels' shear states with them; nothing on rigid
  // ground. (A sandbox raked level before the rover is set down on it again.)
  void level_soil();
  // The soft soil under the wheels (its grid: ruts, volumes), nullptr on rigid ground.
  const soil::SoftSoil* soft_soil() const;
  // The same, to shape the soil (a test's mound or trench, SoilGrid::set_cell_surface_m): the
  // height field the chassis meets takes the change within 10 ms (rover_soft_soil.cpp).
  soil::SoftSoil* soft_soil();
  // The height of the terrain's geoms under (x, y) — the ground, the soft soil's height field,
  // the obstacles; what the chassis meets — by a vertical ray from 1 km up; NaN where it misses.
  double terrain_height_m(double x_m, double y_m) const;
  // Whether MuJoCo now collides the chassis with the soft soil's height field: only while some
  // chassis geom comes within 2 cm of the soil under it (rover_soft_soil.cpp); false on rigid
  // ground.
  bool soil_field_met() const;
  // A weight strapped to a wheel's rim (Procedure 4.13): a gravity torque peak·sin φ on the
  // wheel's hinge, φ its angle (0: the weight at the top). 0 removes it. The stand keeps the
  // chassis level, so φ is measured from the vertical.
  void strap_weight(std::size_t wheel, double peak_torque_nm);
  // Procedure 3.4's hand on an exterior axle (0 front, 1 rear): it turns the axle's roll θ
  // relative to the center axle toward `tilt_rad` at kAxleHandRateRadps and holds it there,
  // rigidly (the hinge follows the hand exactly, without overshoot); a target beyond the hinge's
  // stops ±kMaxAxleTiltRad rests the axle on the stop. nullopt lets the axle go.
  // std::out_of_range for an axle other than 0, 1; std::invalid_argument for a non-finite angle.
  void hold_axle_tilt(std::size_t axle, std::optional<double> tilt_rad);

  // How many warnings MuJoCo raised (instability, contact buffer full, …): 0 in a healthy run.
  int mujoco_warning_count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace marsokhod::sim
