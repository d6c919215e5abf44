// What the driver keeps of its joints across a restart of the onboard computer (a brown-out, a
// crash of the driver process), so that it need not assume the joints vertical again.
//
// Procedure 4.3 sets p⁰ = p̄⁰ of Remark 3.1 on the assumption that the joints stand vertical. A
// driver that restarts after a brown-out in the middle of a gait finds them anywhere in (5.3);
// re-running the procedure there took the driver's p up to 0.28 rad away from the truth, and the
// joint control then drove the joints out of their bounds by as much. But µ6 and µ7 run on their
// own regulators and stay powered through the computer's brown-out (it reboots below 19.5 V, the
// controllers run down to a few volts): their enc, stp and dir registers go on counting what the
// shafts do while the driver is down. So the driver keeps, after every cycle, per joint:
//   the registers (enc, stp, dir) of µj's last 0xj1 response, the shaft position p̄ it gave,
//   the joint position p of (4.1) after it, how far p̄ may be off (the position's uncertainty,
//   motor_position.hpp: carried on and added to),
// and the duty cycle d it sent µj in that cycle. A restarted driver continues from there: the
// first 0xj1 response it receives gives the shaft's movement since the kept reading from the
// registers, which went on counting:
//   T = (enc − enc_kept) mod 65536   every pulse since, whatever the direction;
//   no reversal since (dir and stp as kept):  Δ = (−1)^dir · T;
//   else stp (the last reversal) must lie on the arc enc_kept → enc, A = (stp − enc_kept) mod
//   65536 pulses before it and L = T − A after it:  Δ = s·A + (−1)^dir · L,
// so p̄ = p̄_kept + Δ·2π/115000, and (4.1) applied at the reversal point and at the end gives p
// — until the driver has taken up the gaps where the joints stand (startup.hpp): (4.1) cannot
// see a joint that swung through its gap when µ8's switch stopped its shaft abruptly.
// The sign s of the pulses before the last reversal: with dir changed (one reversal, or an odd
// number) the kept direction (−1)^dir_kept; with dir as kept but stp moved (two or more) the
// direction of the duty d the shaft was left running at — the others are chatter: a shaft that
// slows or stops chatters by a pulse or a few (the simulator's joint motors by 1–3 pulses as a
// slow gait reverses them and as µ8's switch stops them); at rest (d = 0) the direction it
// reversed from last, −(−1)^dir. Each pulse of chatter counted the wrong way errs by two
// pulses (0.0001 rad).
//
// The shaft turns at the duty d the driver sent last until µ8's dead man's switch stops it
// 0.2621·dog s after the last request: the kept d bounds the movement. A state is refused —
// the joints are then unknown, see Driver — when the registers do not continue it:
//   - stp changed but lies off the arc from the kept enc to the new one;
//   - Δ is larger than the motor turns at the no-load speed of |d| (w_max·|d|, with the supply
//     up to 25 % above nominal) for the dead man's delay plus a cycle, plus a cycle at the duty
//     before it (|d| + max_duty_step), plus kReboundRad;
//   - Δ goes against d by more than a cycle at direction_change_duty (the largest duty that
//     may precede a reversal of d) plus kReboundRad;
//   - with the switch off (dog = 0) only half the counter's range (32768 pulses) bounds Δ.
// A controller reset while the driver was down reads stp = 0, dir = 0 and the pulses since its
// reset, and passes these tests only by chance (about 1 in 10⁴ with the joints at rest when it
// was kept, a few in 100 in a fast gait). The host also refuses a kept state older than
// safety.joint_memory_max_age_s (a reboot takes about 30 s; yesterday's state is not today's).
#pragma once

#include <array>
#include <optional>
#include <string>

#include "core/params.hpp"
#include "core/tracking/motor_position.hpp"

namespace marsokhod::driver {

struct KeptJoint {
  tracking::EncoderReading reading;  // µj's last enc, stp, dir
  double shaft_rad = 0.0;            // p̄ at that reading
  double joint_rad = 0.0;            // p of (4.1) after it
  double duty = 0.0;                 // d sent µj in that cycle
  double uncertainty_rad = 0.0;      // how far p̄ may be off (motor_position.hpp), carried on
  bool operator==(const KeptJoint& other) const = default;
};

struct JointMemory {
  // false: the driver that kept it did not know its joints either (a refused state not yet
  // recalibrated); a driver restarted with it holds the joints at once.
  bool known = true;
  std::array<KeptJoint, 2> joints{};  // front (µ6), rear (µ7)
  bool operator==(const JointMemory& other) const = default;
};

struct RestoredJoint {
  double shaft_rad = 0.0;  // p̄ now
  double joint_rad = 0.0;  // p now
  double shift_rad = 0.0;  // how far the shaft turned while the driver was down
};

// A stopping shaft's rebound a kept state allows for beyond what the duty explains: 12× the
// simulator's 3 pulses (0.0002 rad).
inline constexpr double kReboundRad = 0.002;

// The movement a kept state may explain (see above) [rad]: along d, and against it.
struct ShiftBounds {
  double along_rad = 0.0;
  double against_rad = 0.0;
};
ShiftBounds kept_joint_shift_bounds(const Params& params, double duty);

// A restarted driver's first reading of µj against what was kept. `why` receives the reason of
// a refusal ("µ6's stp 1234 does not continue the kept 4321 (reset, or two reversals)").
// Throws std::invalid_argument for a non-finite kept position or backlash_rad < 0.
std::optional<RestoredJoint> restore_joint(const KeptJoint& kept,
                                           const tracking::EncoderReading& now,
                                           double backlash_rad, const Params& params,
                                           std::size_t motor, std::string& why);

}  // namespace marsokhod::driver
