// Procedure 3.3: the ±g table of the accelerometer, axis by axis. The rover rests on the stand
// with one axis x_i along the vertical, first pointing up, then down; µ8's raw acc^i averaged
// over the rest is the table's entry:
//   axis i up   (gravity along −x_i): acc^i(+g), (3.5) gives a_i = −9.81 (the level rover's x3)
//   axis i down (gravity along +x_i): acc^i(−g), (3.5) gives a_i = +9.81
// So on level ground acc³ reads its +g entry (376, the TYP of chapter 3.3's table).
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "calibration/procedure.hpp"
#include "core/params.hpp"

namespace marsokhod::calibration {

// One of the six placements, with every raw reading taken while the rover rested there.
struct AccelerometerPlacement {
  std::size_t axis = 0;  // 0, 1, 2 for x1, x2, x3
  bool axis_up = true;   // x_i points up (the +g entry) or down (the −g entry)
  std::vector<std::array<double, 3>> readings_counts;  // acc¹, acc², acc³ per cycle
};

struct AccelerometerLimits {
  std::size_t min_samples = 64;  // per placement (1 s at 64 Hz)
  // At rest the readings scatter by the sensor's noise (< 1 count σ); more means the rover moves,
  // swings on the stand, or the sensor is faulty.
  double max_rest_sd_counts = 2.0;
  // The span acc(+g) − acc(−g) of each axis must lie within this factor of the configured span
  // (and have its sign): otherwise a placement was wrong or the axis is dead.
  double min_span_ratio = 0.6;
  double max_span_ratio = 1.5;
  // The two axes across gravity must read within this fraction of their span from their own mid
  // reading (a tilt of about asin(2·0.15) ≈ 17° or more shows a wrong placement).
  double max_cross_axis_fraction = 0.15;
};

// The six placements in the order the procedure asks for them: x1 up, x1 down, x2 up, …
struct StandPose {
  std::size_t axis = 0;
  bool axis_up = true;
  double roll_rad = 0.0;   // BenchSetup::stand_roll_rad
  double pitch_rad = 0.0;  // BenchSetup::stand_pitch_rad
  std::string instruction;
};
const std::array<StandPose, 6>& accelerometer_poses();

// The ±g table from the six placements (any order, each (axis, direction) once); `configured`
// is the table the plausibility of the spans is judged against.
ProcedureResult fit_accelerometer(const std::vector<AccelerometerPlacement>& placements,
                                  const SensorParams& configured,
                                  const AccelerometerLimits& limits = {});

}  // namespace marsokhod::calibration
