// The simulated rover's electrics: eight motor models, the supply (battery or tether), the base
// load of chapter 3.1 and the onboard computer's brown-out. Pure and deterministic: time comes in
// as dt_s, nothing is read from a clock.
//
// One step per physics step, in this order:
//   1. currents: each bridge's I from the torque and speed the physics reported for the step just
//      done, under the duty cycle that was in force during it (motor_model.hpp), plus the base
//      load 0.13 + 0.23 A and, while the computer is on, 0.69 A (chapter 3.1: 1.05 A in all);
//   2. supply: U after dt_s with that current (battery.hpp / tether_supply.hpp);
//   3. brown-out: U < 19.5 V switches the computer off for reboot_s (computer_power.hpp);
//   4. drive: the motors' lags advance toward (d, U, icr) and give the speed–torque lines the
//      physics applies during the next step.
// U is thus one step old when it sets the no-load speeds, which breaks the algebraic loop
// U → ω0 → τ → I → U at a delay of one physics step (1 ms).
#pragma once

#include <array>
#include <cstdint>
#include <variant>

#include "core/params.hpp"
#include "sim/electrics/battery.hpp"
#include "sim/electrics/computer_power.hpp"
#include "sim/electrics/motor_model.hpp"
#include "sim/electrics/sim_truth.hpp"
#include "sim/electrics/tether_supply.hpp"

namespace marsokhod::sim {

using IcrVector = std::array<int, kMotorCount>;

struct ElectricsInput {
  MotorVector duty{};  // d_i = (−1)^drv·pwm/icr, from µ0–µ7, for the coming step
  IcrVector icr{511, 511, 511, 511, 511, 511, 511, 511};
  MotorVector shaft_speed_radps{};  // ω_i at the end of the step just done
  MotorVector shaft_torque_nm{};    // τ_i the motors delivered during it
};

struct ElectricsOutput {
  MotorDriveCommand drive;        // for the next physics step
  MotorVector motor_current_a{};  // per bridge, during the step just done
  double base_load_a = 0.0;
  double total_current_a = 0.0;
  double peak_total_current_a = 0.0;  // the largest total_current_a of any step so far
  double supply_v = 0.0;  // U after the step just done
  bool computer_on = true;
  double reboot_remaining_s = 0.0;
  std::uint64_t brownout_count = 0;
  double state_of_charge = 1.0;  // battery; 1 on the tether
};

class RoverElectrics {
 public:
  // Throws std::invalid_argument for invalid supply or brown-out parameters.
  explicit RoverElectrics(const SimTruth& truth);

  const ElectricsOutput& step(const ElectricsInput& input, double dt_s);
  const ElectricsOutput& output() const { return output_; }
  const MotorModel& motor(std::size_t index) const { return motors_.at(index); }
  const PowerTruth& power() const { return power_; }

  // Faults, switchable at run time. Sag: an extra series resistance in the supply path, or a
  // battery that is emptier than it should be (ignored on the tether).
  void set_extra_series_resistance_ohm(double resistance_ohm);
  void set_state_of_charge(double state_of_charge);
  void force_brownout();
  // The laboratory supply's set voltage; throws std::invalid_argument on the battery or outside
  // 0..30 V.
  void set_tether_voltage(double set_v);

 private:
  double base_load_a() const;
  double supply_step(double current_a, double dt_s);
  double supply_voltage_v(double current_a) const;

  PowerTruth power_;
  std::array<MotorModel, kMotorCount> motors_;
  std::variant<Battery, TetherSupply> supply_;
  ComputerPower computer_;
  MotorVector previous_duty_{};
  IcrVector previous_icr_{511, 511, 511, 511, 511, 511, 511, 511};
  ElectricsOutput output_;
};

}  // namespace marsokhod::sim
