// Chapter 3.3: one 0x81 response of µ8 per cycle → the rover's sensor state in physical units.
//
// Per update k, with the conversions of sensor_conversion.hpp:
// - yaw rate ω3 = 0.0170·(y^k − yaw^k) (3.4), then the null-rate filter y^(k+1) (gyro_null.hpp),
//   which moves only while the driver reports the rover still;
// - accelerations a_i by (3.5) on the three axes;
// - tilt: µ8 sends tltᶠ and tltʳ on alternate cycles (bit j of b7), so the state keeps the
//   latest θf and θr, each flagged as seen once its channel has arrived;
// - supply voltage U (Procedure 3.5) and the reference Ū^(k+1) (reference_voltage.hpp), which
//   decays toward U only while the driver reports all duty cycles zero.
// The filters' values in the state are those after the update (y^(k+1), Ū^(k+1)), the ones the
// next cycle will use; U^k ≤ Ū^(k+1) always.
#pragma once

#include <array>
#include <cstdint>

#include "core/params.hpp"
#include "core/protocol/messages.hpp"
#include "core/tracking/gyro_null.hpp"
#include "core/tracking/reference_voltage.hpp"

namespace marsokhod::tracking {

struct SensorState {
  double yaw_rate_radps = 0.0;         // ω3 around x3, (3.4)
  std::array<double, 3> accel_mps2{};  // a_acc along x1, x2, x3 of the sensor, (3.5)
  double front_tilt_rad = 0.0;         // θf, the latest seen (0 until seen)
  double rear_tilt_rad = 0.0;          // θr, the latest seen (0 until seen)
  bool front_tilt_seen = false;
  bool rear_tilt_seen = false;
  protocol::TiltChannel latest_tilt_channel = protocol::TiltChannel::kFront;
  double supply_v = 0.0;            // U
  double reference_supply_v = 0.0;  // Ū, never below U
  double gyro_null_counts = 0.0;    // y after this update
  std::uint64_t update_count = 0;   // responses processed so far
};

class SensorTracker {
 public:
  // Validates both parameter sets; throws std::invalid_argument naming the first bad parameter.
  SensorTracker(const SensorParams& sensors, const FilterParams& filters);

  // Feeds µ8's response of this cycle. rover_still: nothing moves (the driver's judgement, e.g.
  // all wheel and joint velocities zero); all_duty_zero: d_i = 0 for all eight motors this cycle.
  // Throws std::invalid_argument if a reading exceeds 10 bits; the state is unchanged then.
  const SensorState& update(const protocol::MeasurementResponse& response, bool rover_still,
                            bool all_duty_zero);

  const SensorState& state() const { return state_; }

 private:
  SensorParams sensors_;
  GyroNullFilter gyro_null_;
  ReferenceVoltage reference_voltage_;
  SensorState state_;
};

}  // namespace marsokhod::tracking
