// Chapter 3.2: the accumulated angular position p̄ of one motor shaft from enc, stp and dir.
//
// The controller's 16-bit enc counts encoder pulses regardless of direction, dir is the measured
// direction (0 = counter-clockwise around x2 = positive), and stp is enc at the last measured
// direction change (refreshed only while eim = 1). Per docs/design.md's reading of the chapter's formula,
// the signed pulse count between two readings is
//   same direction:   Δ = (enc^k − enc^(k−1)) mod 65536
//   direction change: Δ = ((stp^k − enc^(k−1)) mod 65536) − ((enc^k − stp^k) mod 65536)
// and  p̄^k = p̄^(k−1) + (−1)^dir^(k−1) · 2π/115000 · Δ   [rad].
// The printed formula takes one modulo over a difference that can be negative; counting the two
// parts separately is what the registers mean. 65536 counts are 2π·65536/115000 = 3.58 rad
// (205 deg; the text's "102.6 deg" contradicts its own conversion).
//
// Limits, by construction of the registers:
// - Two direction changes inside one cycle leave dir as it was; the printed formula's first case
//   counts the pulses between the changes in the old direction, an error of twice their number.
//   The registers do show that it happened: stp moved (it points at the second change) while dir
//   stayed. They do not show how the pulses before that change split into forward and back, so
//   those pulses count as net zero, the midpoint of [−a, a] (a = (stp^k − enc^(k−1)) mod 65536),
//   and the pulses after it in the direction dir reads:
//     dir unchanged, stp^k ≠ stp^(k−1), stp^k on the arc: Δ = (enc^k − stp^k) mod 65536.
//   The error is then at most a instead of up to 2a (the truth's x − y lies in [−a, a − 2]: stp
//   is taken before the first pulse in a new direction, so at least one went back); the tracker
//   sums those a as the position's uncertainty. It matters where a joint sticks and slips:
//   its coupling springs the shaft back a few pulses and forward again inside one 15.6 ms cycle
//   every stroke (RELIABILITY.md, rear-wheel-walking-slope-slant-off).
// - More than 65535 pulses (3.58 rad) between two readings wrap unseen; at the no-load speed
//   w = 2.827 rad/s that takes 1.27 s of missed responses.
// - If dir changed but stp does not lie on the arc enc^(k−1) → enc^k (stp not refreshed, e.g.
//   eim = 0), the point of reversal is unknown. Then Δ = 0, the midpoint estimate: the true Δ lies
//   in ±(enc^k − enc^(k−1)) mod 65536, and the formula above could jump by up to 3.58 rad.
#pragma once

#include <cstdint>

namespace marsokhod::tracking {

// The three registers of a 0xi1 response that carry the position.
struct EncoderReading {
  std::uint16_t enc = 0;  // pulses, modulo 65536
  std::uint16_t stp = 0;  // enc at the last measured direction change
  bool dir = false;       // measured direction: false = positive (counter-clockwise around x2)
  bool operator==(const EncoderReading& other) const = default;
};

// Signed pulses from previous to current, positive in the positive direction (dir = 0).
struct PositionIncrement {
  std::int32_t counts = 0;
  bool reversal_point_unknown = false;  // dir changed but stp was not on the arc; counts = 0
  bool hidden_reversals = false;  // dir unchanged but stp moved: the pulses before stp count 0
};

// Chapter 3.2 as read in docs/design.md, including the sign (−1)^dir^(k−1).
PositionIncrement position_increment(const EncoderReading& previous, const EncoderReading& current);

// 2π / encoder_pulses_per_rev [rad per pulse]. Throws std::invalid_argument unless pulses > 0.
double encoder_rad_per_count(int encoder_pulses_per_rev);

// Accumulates p̄ over the readings of one motor. The first reading only sets the reference:
// p̄⁰ = initial_position_rad (Remark 3.1: joints vertical, ∓1.2121 rad, wheels 0). Pulses are
// summed as integers, so p̄ carries no rounding drift however far the motor turns.
class PositionTracker {
 public:
  // Throws std::invalid_argument if initial_position_rad is not finite or pulses ≤ 0.
  PositionTracker(double initial_position_rad, int encoder_pulses_per_rev);

  // Feeds reading k; returns p̄^k [rad].
  double update(const EncoderReading& reading);

  bool started() const { return started_; }
  double position_rad() const { return position_rad_; }
  std::int64_t accumulated_counts() const { return accumulated_counts_; }
  // How many direction changes arrived with an stp off the arc (counted as Δ = 0).
  std::uint64_t unknown_reversal_count() const { return unknown_reversal_count_; }
  // How many readings showed stp moved while dir stayed (two changes inside one cycle).
  std::uint64_t hidden_reversal_count() const { return hidden_reversal_count_; }
  // How far p̄ may be off for what the registers hid, in pulses, summed since the first reading:
  // a for each hidden pair (the midpoint's error is at most a), the whole arc for each reversal
  // with an unknown point (Δ = 0 there, the truth within ± the arc). Lost pulses are not in it:
  // nothing shows them.
  std::uint64_t uncertainty_counts() const { return uncertainty_counts_; }
  // The registers of the last reading (meaningful once started).
  const EncoderReading& last_reading() const { return previous_; }

 private:
  double initial_position_rad_;
  double rad_per_count_;
  double position_rad_;
  std::int64_t accumulated_counts_ = 0;
  std::uint64_t unknown_reversal_count_ = 0;
  std::uint64_t hidden_reversal_count_ = 0;
  std::uint64_t uncertainty_counts_ = 0;
  EncoderReading previous_{};
  bool started_ = false;
};

}  // namespace marsokhod::tracking
