// The simulated rover as the driver meets it: CAN frames in, CAN frames out, with the bus'
// timing, and nothing else. Inside, every physics step (1 ms):
//   firmware (µ0–µ8 see the shaft angles, the IMU and the supply) → duty cycles
//   → electrics (motors' no-load speed, droop, stall; supply voltage, brown-out)
//   → physics (MuJoCo: chassis, joints with backlash, wheels on the terrain) → shaft angles.
// The loop closes through one physics step of delay, as a real controller samples its inputs.
// Ground truth and fault switches are a C++ API for tests, scenarios and the console's 3-D view,
// never on the bus. Deterministic: the same options and seed give the same frames, bit for bit.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/params.hpp"
#include "core/protocol/can_frame.hpp"
#include "sim/electrics/rover_electrics.hpp"
#include "sim/electrics/sim_truth.hpp"
#include "sim/firmware/rover_firmware.hpp"
#include "sim/physics/rover_physics.hpp"
#include "sim/physics/terrain.hpp"

namespace marsokhod::sim {

struct SimOptions {
  std::uint64_t seed = 1;
  TerrainSpec terrain = TerrainSpec{};
  double physics_timestep_s = 0.001;
  bool nominal_unit = false;  // true: the configured ζ, ±g table … (exact_sim_truth), else drawn
  SupplyKind supply = SupplyKind::kBattery;
  // A unit given explicitly (tests): the same rover under different driver configurations, e.g.
  // nominal and calibrated Params. Overrides seed's draw and nominal_unit; supply still applies.
  std::optional<SimTruth> unit;
  // Empty: the emulated controllers (sim/firmware). Else a folder with the real firmware images
  // mu0.elf … mu8.elf (`make firmware`), run in simavr (sim/avr/rover_hardware.hpp).
  std::string firmware_dir;
};

// A frame the rover's controllers put on the bus, and when the driver side has it.
struct TimedFrame {
  double time_s = 0.0;
  protocol::CanFrame frame;
};

// Faults of the issue, each switchable at run time.
struct SimFaults {
  std::array<bool, kWheelCount> wheel_blocked{};     // a rigid wheel (Field Experiment 6.2)
  std::array<bool, kWheelCount> wheel_no_contact{};  // a wheel without ground contact
  std::array<bool, 2> joint_jammed{};                // a joint that cannot bend (front, rear)
  std::array<double, kMotorCount> lost_pulse_fraction{};  // a loose encoder connection
  std::array<bool, kMotorCount + 1> silent{};        // µ0–µ8 never answer
  double frame_loss_probability = 0.0;
  double extra_series_resistance_ohm = 0.0;          // battery sag
};

class SimulatedRover {
 public:
  SimulatedRover(const Params& nominal, const SimOptions& options);

  // A frame from the driver side, put on the bus at time_s (≥ the rover's time). While the
  // onboard computer is browned out (below 19.5 V, for the reboot time) nothing it sends reaches
  // the bus: the frame is dropped and counted.
  void send(const protocol::CanFrame& frame, double time_s);
  // Runs the rover to time_s and returns the frames its controllers delivered since the last
  // call, in bus order — none while the onboard computer is down: the bus stops answering the
  // driver, and µ8's dead man's switch, no longer fed, stops the motors.
  std::vector<TimedFrame> advance_to(double time_s);
  std::uint64_t frames_dropped_during_brownout() const { return dropped_; }
  MotorVector shaft_torque_nm() const { return physics_.shaft_torque_nm(); }  // per motor

  double time_s() const;
  bool computer_on() const { return electrics_.output().computer_on; }
  const ElectricsOutput& electrics() const { return electrics_.output(); }
  GroundTruth truth() const { return physics_.truth(); }
  ImuTruth imu() const { return physics_.imu(); }
  const RoverFirmware& firmware() const { return firmware_; }
  const SimTruth& sim_truth() const { return truth_; }
  double energy_used_j() const { return energy_j_; }
  std::uint64_t physics_steps() const { return steps_; }

  const SimFaults& faults() const { return faults_; }
  void set_faults(const SimFaults& faults);  // throws std::invalid_argument for a bad value
  void force_brownout() { electrics_.force_brownout(); }
  // A battery emptier than new (ignored on the tether); throws std::invalid_argument.
  void set_state_of_charge(double state_of_charge) {
    electrics_.set_state_of_charge(state_of_charge);
  }

  // The calibration bench's hands (Procedures 3.3, 3.5, 4.4–4.13), never reachable from the bus:
  // the tether's set voltage (std::invalid_argument on the battery), the stand and strapped
  // weights (rover_physics.hpp).
  void set_tether_voltage(double set_v) { electrics_.set_tether_voltage(set_v); }
  void place_on_stand(double roll_rad, double pitch_rad) {
    physics_.place_on_stand(roll_rad, pitch_rad);
  }
  void place_on_ground() { physics_.place_on_ground(); }
  bool on_stand() const { return physics_.on_stand(); }
  void level_soil() { physics_.level_soil(); }  // RoverPhysics::level_soil
  const soil::SoftSoil* soft_soil() const { return physics_.soft_soil(); }  // nullptr: rigid
  void strap_weight(std::size_t wheel, double peak_torque_nm) {
    physics_.strap_weight(wheel, peak_torque_nm);
  }
  // Procedure 3.4: an exterior axle turned by hand and held (RoverPhysics::hold_axle_tilt).
  void hold_axle_tilt(std::size_t axle, std::optional<double> tilt_rad) {
    physics_.hold_axle_tilt(axle, tilt_rad);
  }

 private:
  SensorTruthSample sensor_sample() const;
  void physics_step();

  const Params* params_;
  SimTruth truth_;
  RoverPhysics physics_;
  Params firmware_params_;  // the encoders count from the physics' initial shaft angles
  RoverElectrics electrics_;
  RoverFirmware firmware_;
  SimFaults faults_;
  double energy_j_ = 0.0;
  std::uint64_t dropped_ = 0;
  std::uint64_t steps_ = 0;
};

}  // namespace marsokhod::sim
