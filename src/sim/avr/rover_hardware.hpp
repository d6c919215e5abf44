// The nine controllers as their real firmware in simavr: µ0–µ7 from DIR/mu0.elf … mu7.elf and µ8
// from DIR/mu8.elf (`make firmware` builds them into build/firmware), behind RoverFirmware's bus
// in place of the emulation (`marsokhod sim --firmware DIR`, `scenario --firmware DIR`).
//
// µ8's analog inputs are the emulation's (sensor_adc.hpp): the true state through the unit's
// conversions run backwards, the tilt potentiometers behind their backlash, Gaussian noise of the
// unit's size drawn from the run's seed whenever the inputs are updated, then rounded to counts.
// A loose encoder connection drops each pulse with the given probability (seeded), as in the
// emulation.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/params.hpp"
#include "sim/avr/motor_firmware.hpp"
#include "sim/avr/sensor_firmware.hpp"
#include "sim/electrics/seeded_random.hpp"
#include "sim/electrics/sim_truth.hpp"
#include "sim/firmware/controller_hardware.hpp"
#include "sim/firmware/sensor_adc.hpp"

namespace marsokhod::sim::avr {

class RoverHardware final : public ControllerHardware {
 public:
  // Throws std::runtime_error naming the image that is missing or unreadable.
  RoverHardware(const std::string& firmware_dir, const Params& params, const SensorTruth& sensors,
                std::uint64_t seed, const SensorTruthSample& initial_sensors);

  void advance(SimTimeNs time_ns, const MotorVector& shaft_angle_rad,
               const SensorTruthSample& sensors) override;
  void deliver(const protocol::CanFrame& frame) override;
  std::vector<HardwareTransmission> take_transmitted() override;
  MotorVector duty() const override;
  IcrVector icr() const override;
  void set_lost_pulse_fraction(std::size_t motor, double fraction) override;

 private:
  SensorCounts counts(const SensorTruthSample& sample, SimTimeNs time_ns);

  std::vector<std::unique_ptr<MotorFirmware>> motors_;
  SensorFirmware sensor_;
  SensorTruth truth_;
  PotentiometerBacklash front_pot_;
  PotentiometerBacklash rear_pot_;
  SeededRandom noise_;
};

}  // namespace marsokhod::sim::avr
