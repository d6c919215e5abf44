// The nine emulated controllers on their CAN bus: what the driver's CAN interface talks to.
//
// The onboard computer (the driver) puts frames on the bus with send(); advance_to() then runs
// bus and controllers to a time, the physics' shaft angles and sensor truth at that time in hand:
//   - the bus arbitrates and times every frame (can_bus_model.hpp);
//   - a delivered request reaches its controller at its delivery time, with the shaft angles
//     interpolated linearly between the previous advance_to() and this one; the controller's
//     answer is ready response_latency_s (50 µs) later and competes for the bus like any frame;
//   - µ8's dead man's switch puts its eight stop frames on the bus at its deadline, before any
//     arbitration that starts at or after it.
// advance_to() returns every frame delivered on the bus that the driver did not send itself
// (responses, and µ8's stop frames), in bus order with their times.
// Faults (run time): a controller that never answers (silent: it still receives and acts, its
// transmitter is dead; a silent µ8 sends no stop frames either), frame loss on the bus (seeded;
// the stop frames it takes are counted per motor), a loose encoder connection per motor
// (motor_controller.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/params.hpp"
#include "core/protocol/can_frame.hpp"
#include "sim/electrics/rover_electrics.hpp"
#include "sim/electrics/sim_truth.hpp"
#include "sim/firmware/can_bus_model.hpp"
#include "sim/firmware/controller_hardware.hpp"
#include "sim/firmware/motor_controller.hpp"
#include "sim/firmware/sensor_controller.hpp"
#include "sim/firmware/sim_time.hpp"

namespace marsokhod::sim {

inline constexpr std::size_t kControllerCount = kMotorCount + 1;  // µ0–µ8

class RoverFirmware {
 public:
  // Shafts start at params.motors.initial_position_rad (Remark 3.1); the seed feeds the bus's
  // loss draws, each controller's lost pulses and µ8's noise, each from its own stream.
  RoverFirmware(const Params& params, const SimTruth& truth, std::uint64_t seed,
                const SensorTruthSample& initial_sensors = {});
  // The same bus with the controllers on other hardware (the real firmware, controller_hardware.hpp)
  // instead of the emulation: frames go to it, its transmissions go on the bus at their times,
  // duty and icr come from it; silence and frame loss stay the bus's faults here.
  RoverFirmware(const Params& params, const SimTruth& truth, std::uint64_t seed,
                const SensorTruthSample& initial_sensors,
                std::unique_ptr<ControllerHardware> hardware);

  // A frame from the driver, on the bus from ready_ns on. Throws std::invalid_argument for a
  // frame no CAN bus carries.
  void send(const protocol::CanFrame& frame, SimTimeNs ready_ns);

  // Runs to time_ns (not before the previous call). Throws std::invalid_argument if time goes back.
  std::vector<BusDelivery> advance_to(SimTimeNs time_ns, const MotorVector& shaft_angle_rad,
                                      const SensorTruthSample& sensors);

  // d_i = (−1)^drv·pwm/icr and icr of µ0–µ7 now: the electrics' input.
  MotorVector duty() const;
  IcrVector icr() const;
  SimTimeNs time_ns() const { return time_ns_; }

  const MotorController& motor_controller(std::size_t motor) const { return motors_.at(motor); }
  const SensorController& sensor_controller() const { return sensor_; }
  const CanBusModel& bus() const { return bus_; }
  // µ8's frames to µi (its dead man's stop frames) that the loss fault took, since the start.
  const std::array<std::uint64_t, kMotorCount>& stop_frames_lost() const {
    return stop_frames_lost_;
  }

  void set_silent(std::size_t controller, bool silent);
  void set_frame_loss_probability(double probability);
  void set_lost_pulse_fraction(std::size_t motor, double fraction);

 private:
  void move_controllers_to(SimTimeNs time_ns);
  void deliver(const BusDelivery& delivery);
  void answer(std::size_t controller, const std::optional<protocol::CanFrame>& response,
              SimTimeNs received_ns);
  bool fire_dead_man_if_due(SimTimeNs until_ns);
  bool enqueue_hardware_transmissions();

  std::unique_ptr<ControllerHardware> hardware_;  // null: the emulation answers

  std::vector<MotorController> motors_;
  SensorController sensor_;
  CanBusModel bus_;
  SimTimeNs latency_ns_;
  std::array<bool, kControllerCount> silent_{};
  std::array<std::uint64_t, kMotorCount> stop_frames_lost_{};
  SimTimeNs time_ns_ = 0;
  MotorVector angle_rad_{};  // at time_ns_
  SimTimeNs target_ns_ = 0;  // the step being run: from time_ns_ to target_ns_
  MotorVector target_angle_rad_{};
  SensorTruthSample target_sensors_;
};

}  // namespace marsokhod::sim
