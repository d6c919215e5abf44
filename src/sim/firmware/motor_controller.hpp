// Emulation of the firmware of one motor controller µ0–µ7 (AT90CAN128, chapter 3.2), byte-exact
// on the bus through the protocol codec.
//
// Registers and what drives them:
// - icr, pwm, drv, eim, con: written by 0xi0 (drv, eim, pwm) and 0xi2 (icr, pwm, con). Reset
//   values: icr = 511 (the thesis' compromise), everything else 0.
// - tim: Timer at 2 MHz/(con+1), 16 bit. A change of con keeps the count and restarts the
//   prescaler at the moment the 0xi2 arrives.
// - enc: Timer 3 counts the encoder's pulses on T3, 115000 per revolution of the shaft, whatever
//   the direction. From the shaft angle: every pulse boundary k·2π/115000 crossed counts once, in
//   either direction (the loose-connection fault skips a seeded fraction of them).
// - dir, stp: INT0 fires on the LS7184's direction line. When a pulse is crossed in the direction
//   opposite to the line's, the line flips; with eim = 1 the interrupt sets stp = enc (before
//   that pulse) and dir to the new direction. With eim = 0 the interrupt is masked: neither dir
//   nor stp changes, and since INT0 is edge-triggered a later eim = 1 does not resynchronise dir
//   until the next measured change (the driver keeps eim = 1 below 60 % duty, where reversals
//   happen).
// - vel: the pulses of the last period T(con), kept as a moving window of S slices of T(con)/S:
//   whenever tim crosses a multiple of 65536/S the firmware stores the slice's pulse count in a
//   ring and vel becomes the sum of the last S slices, saturated to 15 bits (0x7FFF; only
//   con ≥ 18 at full speed could exceed it). S = 1 is the plain reading "pulses counted between
//   the last two overflows of tim"; the default S = 16 (ControllerTruth) ends the window at most
//   T/16 before the response, which together with a 12 ms motor lag reproduces the δ table of
//   Procedure 4.8 (S = 1 cannot: its window alone delays w by 2.6 cycles of 15.7 ms on average,
//   the thesis' δ by 2.2). Before S slices have passed, vel sums the slices so far.
// Frames: 0xi0 → 0xi1 (tim, enc, stp, dir, vel), 0xi2 → 0xi3 (tim); the registers are sampled
// when the request arrives. Any frame for another node, any other type, and any frame the codec
// rejects (wrong DLC, reserved bits set, pwm > icr for the icr in force, icr out of 255..2047) is
// ignored without an answer, as the real firmware ignores what it cannot use.
// Duty to the bridge: d = (−1)^drv·pwm/icr.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/protocol/can_frame.hpp"
#include "sim/electrics/seeded_random.hpp"
#include "sim/firmware/sim_time.hpp"

namespace marsokhod::sim {

inline constexpr SimTimeNs kTimerBaseTickNs = 500;  // 2 MHz
inline constexpr std::uint32_t kTimerModulus = 65536;

struct MotorControllerRegisters {
  std::uint16_t icr = 511;
  std::uint16_t pwm = 0;
  bool drv = false;
  bool eim = false;
  std::uint8_t con = 0;
  std::uint16_t tim = 0;
  std::uint16_t enc = 0;
  std::uint16_t stp = 0;
  bool dir = false;
  std::uint16_t vel = 0;
};

class MotorController {
 public:
  // node 0..7; the shaft starts at initial_shaft_angle_rad at time 0.
  // velocity_window_slices S must be a power of two in 1..256. Throws std::invalid_argument if
  // node > 7, pulses_per_rev ≤ 0 or S is not such a power of two.
  MotorController(std::uint8_t node, double initial_shaft_angle_rad, int pulses_per_rev,
                  std::uint64_t seed, int velocity_window_slices = 16);

  // Moves the shaft to shaft_angle_rad at time_ns, linearly from the previous sample, counting
  // pulses and closing a vel slice at every slice boundary of tim on the way. time_ns must not go
  // back.
  void advance(SimTimeNs time_ns, double shaft_angle_rad);

  // A frame delivered at the time of the last advance(): the response, if the firmware answers.
  std::optional<protocol::CanFrame> receive(const protocol::CanFrame& frame);

  // d = (−1)^drv·pwm/icr.
  double duty() const;
  std::uint8_t node() const { return node_; }
  // The registers at the time of the last advance() (tim included).
  MotorControllerRegisters registers() const;
  SimTimeNs time_ns() const { return time_ns_; }

  // The loose encoder connection: each pulse is lost with this probability (0 = healthy).
  void set_lost_pulse_fraction(double fraction);

 private:
  SimTimeNs tick_ns() const { return kTimerBaseTickNs * (registers_.con + 1); }
  std::uint64_t ticks_at(SimTimeNs time_ns) const;
  SimTimeNs next_slice_end_ns() const;
  void close_slice();
  void move_shaft_to(double shaft_angle_rad);
  void count_pulses(std::int64_t pulses, bool negative);
  void change_con(std::uint8_t con);

  std::uint8_t node_;
  double pulses_per_rad_;
  MotorControllerRegisters registers_;
  SimTimeNs time_ns_ = 0;
  double shaft_angle_rad_;
  std::int64_t pulse_index_;    // floor(angle·pulses_per_rad) at the last sample
  bool line_negative_ = false;  // the LS7184's direction line
  // tim = (ticks_before_epoch_ + (t − epoch_start_ns_)/tick) mod 65536 within one con epoch.
  std::uint64_t ticks_before_epoch_ = 0;
  SimTimeNs epoch_start_ns_ = 0;
  std::uint64_t slice_ticks_;
  std::vector<std::uint64_t> slice_pulses_;  // ring of the last S slices
  std::size_t next_slice_ = 0;
  std::uint64_t pulses_this_slice_ = 0;
  double lost_pulse_fraction_ = 0.0;
  SeededRandom random_;
};

}  // namespace marsokhod::sim
