// The nine controllers when they run somewhere else than in this emulation — their real firmware
// in an AVR simulator (sim/avr/rover_hardware.hpp, `--firmware DIR`): what RoverFirmware needs of
// them. RoverFirmware keeps the bus; the hardware sees every delivered frame through its own
// acceptance filters and hands back what it transmits, stamped with the time it had it ready.
#pragma once

#include <cstddef>
#include <vector>

#include "core/protocol/can_frame.hpp"
#include "sim/electrics/rover_electrics.hpp"
#include "sim/firmware/sensor_controller.hpp"
#include "sim/firmware/sim_time.hpp"

namespace marsokhod::sim {

struct HardwareTransmission {
  std::size_t controller = 0;  // 0..8
  SimTimeNs ready_ns = 0;
  protocol::CanFrame frame;
};

class ControllerHardware {
 public:
  virtual ~ControllerHardware() = default;
  // Runs the controllers to time_ns, the shafts at shaft_angle_rad and µ8's sensors as sampled.
  virtual void advance(SimTimeNs time_ns, const MotorVector& shaft_angle_rad,
                       const SensorTruthSample& sensors) = 0;
  // A frame on the bus, delivered at the current time to every controller.
  virtual void deliver(const protocol::CanFrame& frame) = 0;
  // What the controllers sent since the last call, in time order.
  virtual std::vector<HardwareTransmission> take_transmitted() = 0;
  virtual MotorVector duty() const = 0;
  virtual IcrVector icr() const = 0;
  // The loose encoder connection of one motor (0 = healthy).
  virtual void set_lost_pulse_fraction(std::size_t motor, double fraction) = 0;
};

}  // namespace marsokhod::sim
