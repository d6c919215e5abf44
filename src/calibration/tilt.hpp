// Procedure 3.4: the tilt potentiometers θf, θr. "We tilt the front and rear axles with respect to
// the center axle. […] The readings at the limit of ±30 deg are linearly interpolated, similar to
// (3.5)", giving θ = gain·tlt + offset for each (θf = +0.00495 tltᶠ − 2.61, θr = −0.00526 tltʳ +
// 2.74 rad). "The backlash of the potentiometers affect the measurements. The error is about ±8
// deg."
//
// The play b of a potentiometer's shaft makes a reading at a stop, reached from inside, the
// reading of θs − b/2, not θs: fitted through the two stops alone, the gain would come out
// 60°/(60° − b) too large (15 % for 8° of play). So the procedure reads four placements in this
// order, both axles at once:
//   1. turned up against the +30° stop         shaft at +θs − b/2   mean reading m1
//   2. let down to level (θ = 0) from above    shaft at      + b/2  m2
//   3. turned down against the −30° stop       shaft at −θs + b/2   m3
//   4. brought up to level from below          shaft at      − b/2  m4
// Then m1 − m4 and m2 − m3 both span θs exactly, and the mean of the two level readings is θ = 0:
//   gain   = 2·θs / ((m1 − m4) + (m2 − m3))
//   offset = −gain·(m2 + m4)/2
//   b      = gain·(m2 − m4)             (reported; the driver neglects θ, chapter 3.3)
// θs = π/6 (30°), θ > 0 with the left wheel up (the simulator's roll hinge, right-hand about x1).
// µ8 sends tltᶠ and tltʳ in alternate cycles (chapter 3.3's bit j); each placement's readings are
// averaged per channel.
#pragma once

#include <array>
#include <vector>

#include "calibration/procedure.hpp"
#include "core/params.hpp"

namespace marsokhod::calibration {

inline constexpr double kTiltStopRad = 0.5235987755982988;  // ±30°, Procedure 3.4

// One placement: the raw readings of each channel while both axles rested there.
struct TiltPlacement {
  std::vector<double> front_counts;  // tltᶠ
  std::vector<double> rear_counts;   // tltʳ
};

// The four placements in the order above.
using TiltPlacements = std::array<TiltPlacement, 4>;

struct TiltLimits {
  std::size_t min_samples = 32;  // per placement and channel (1 s at 64 Hz, alternating)
  double max_rest_sd_counts = 2.0;  // at rest a reading scatters by its noise only
  // m1 − m4 and m2 − m3 each span θs; more apart than this, an axle was not at its stop or not
  // level, or it moved.
  double max_span_mismatch_counts = 3.0;
  // The fitted gain within this factor of the configured one, and of its sign.
  double min_gain_ratio = 0.6;
  double max_gain_ratio = 1.5;
  double max_play_rad = 0.5;  // a play beyond ~29° (or a negative one): a wrong placement
};

// gain, offset and play of one potentiometer from the means m1…m4 (counts), as above.
struct TiltFit {
  double gain_rad_per_count = 0.0;
  double offset_rad = 0.0;
  double play_rad = 0.0;
  double span_mismatch_counts = 0.0;  // (m1 − m4) − (m2 − m3)
};
TiltFit fit_tilt_channel(const std::array<double, 4>& mean_counts, double stop_rad = kTiltStopRad);

// The [sensors] tilt_front_*, tilt_rear_* values; `configured` is what the gains are judged
// against.
ProcedureResult fit_tilt(const TiltPlacements& placements, const SensorParams& configured,
                         const TiltLimits& limits = {});

}  // namespace marsokhod::calibration
