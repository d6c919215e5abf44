// Failsafes that need an estimate of the rover's state rather than one controller's answer
// (pure, no I/O): the rover tipping over, the rover stuck, a joint blocked. Each turns into a
// latched fault of the driver (driver.cpp), which stops the motors as any fault does.
//
// Tip-over. The accelerometer of µ8 reads the specific force in the chassis frame (x forward,
// y left, z up); at rest it is gravity, a = (0, 0, −g) on level ground. Its readings are averaged
// with the time constant τ (a ← a + min(1, h/τ)·(reading − a)): the blades' vibration on sand
// (about 3 m/s²) must not trip it, a tipping rover must. From the mean, the attitude in REP-103's
// sense:
//   roll  φ = atan2(−a_y, −a_z)                 (+: the left side up)
//   pitch θ = atan2(a_x, √(a_y² + a_z²))        (+: the nose down)
// and the fault when |φ| > φ_max or |θ| > θ_max. The defaults, 40° each, lie above the steepest
// ground the rover climbs (25–30° by wheel walking, at most the granules' angle of repose) and
// well below where it falls over: with its 0.70 m track and its centre of mass about 0.20 m above
// the ground (the 30 kg electronics box at 0.30 m, the 36 kg of wheels at 0.125 m) it rolls over
// at atan(0.35/0.20) = 60°, and pitches over later still (the outer axles 0.56 m from the centre).
//
// Stuck (ArduPilot's crash check, with the wheels' load for the missing speed): driving, the
// operator asking for motion (v1, v2 or a gait's speed not 0: a rover that holds itself on a
// slope at v1 = 0 stalls its wheels on purpose), the centre wheels — the ones the dead reckoning (pose_estimator.hpp) takes the distance from —
// commanded a mean no-load speed ν̄ = (|ν_CL| + |ν_CR|)/2 of at least ν_min turn at
// |w_CL| + |w_CR| ≤ s·(|ν_CL| + |ν_CR|) (the load l = w − ν takes at least 1 − s of the command:
// they are stalled, and the estimate does not advance), and the gyro says the rover does not
// turn (|ω| < ω_min); when that holds for T without a break, the rover is stuck. T = 5 s is
// longer than the longest stall a rover came out of on its own on the simulator's units: 3.6 s,
// starting up a 20° sand slope while the power management (6.3) raises D (slope-slant-on, seed
// 7; 1.5–3.6 s on seeds 1–20, where seeds 15 and 17 stay stalled to the end). The exterior
// wheels do not count: against a wall the front wheels spin on its face while the rover stands
// (a smooth wall in the simulator: 24 % of the six wheels' command), and one rigid wheel is
// dragged by the others (Field Experiment 6.2). A stalled pair is a rover pushing against what it
// cannot climb or bogged down to its axles. A rover whose wheels spin freely in place while it
// does not advance is *not* detected: nothing on board measures its speed over the ground then
// (the accelerometer reads the same at rest and at a constant speed).
//
// Joint blocked: driving, a joint motor commanded a no-load speed |ν| of at least ν_min turns at
// |w| ≤ s·|ν| for T without a break. (4.16) drives a joint toward its target and 6.2.3's axle
// placement moves ρ when the exterior axle cannot go (axle_placement.hpp), but once the joint
// cannot bend by moving either side (a rigid front wheel in soft sand holds the front axle, and
// the chassis cannot follow through the sand: Field Experiment 6.2's broken wheel during wheel
// walking) nothing in the thesis ends the push: the joint motor would stall under its duty for as
// long as the gait asks. A stall longer than T is a fault, named for its joint, that stops the
// rover like the others. The same T, ν_min and s as the stuck check: the longest joint stall on
// the shipped scenarios that came free on its own lasted 1.84 s (docs/decisions.md).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace marsokhod::estimation {

struct TipOverLimits {
  double roll_rad = 0.6981;    // φ_max, 40°
  double pitch_rad = 0.6981;   // θ_max, 40°
  double time_constant_s = 0.25;  // τ
};

struct Attitude {
  double roll_rad = 0.0;   // φ, + left side up
  double pitch_rad = 0.0;  // θ, + nose down
};

class TipOverMonitor {
 public:
  // Throws std::invalid_argument unless the limits are in (0, π/2] and τ > 0, all finite.
  explicit TipOverMonitor(TipOverLimits limits = {});

  // One accelerometer reading [m/s²] after a cycle of h [s]. Readings shorter than a tenth of g
  // (a sensor fault or free fall) do not count. Returns the fault's text when the mean attitude is
  // beyond a limit. Throws std::invalid_argument naming the input when one is not finite or h ≤ 0.
  std::optional<std::string> update(const std::array<double, 3>& accel_mps2, double period_s);

  const Attitude& attitude() const { return attitude_; }

 private:
  TipOverLimits limits_;
  std::array<double, 3> mean_mps2_{0.0, 0.0, -9.81};
  Attitude attitude_;
};

struct StuckLimits {
  double time_s = 5.0;              // T; 0 switches the check off
  double min_command_radps = 0.2;   // ν_min
  double turning_share = 0.2;       // s
  double min_yaw_rate_radps = 0.1;  // ω_min
};

struct StuckInput {
  double period_s = 0.0;
  std::array<double, 2> no_load_radps{};   // ν_CL, ν_CR of (4.4): µ2, µ3
  std::array<double, 2> velocity_radps{};  // w_CL, w_CR, measured
  double yaw_rate_radps = 0.0;            // ω
  bool driving = false;                   // the driver is in driving mode
  bool motion_asked = false;              // the operator's v1, v2 or gait speed is not 0
};

class StuckMonitor {
 public:
  // Throws std::invalid_argument unless T ≥ 0, ν_min > 0, s in [0, 1) and ω_min > 0, all finite.
  explicit StuckMonitor(StuckLimits limits = {});

  // One cycle. Returns the fault's text in the cycle the stall has lasted T. Throws
  // std::invalid_argument naming the input when one is not finite or h ≤ 0.
  std::optional<std::string> update(const StuckInput& input);

  // How long the wheels have been stalled without a break [s].
  double stalled_s() const { return stalled_s_; }

 private:
  StuckLimits limits_;
  double stalled_s_ = 0.0;
  double turned_sum_ = 0.0;   // ∫Σ|w| dt and ∫Σ|ν| dt over the stall, for the fault's text
  double command_sum_ = 0.0;
};

struct JointBlockedLimits {
  double time_s = 5.0;             // T; 0 switches the check off
  double min_command_radps = 0.2;  // ν_min
  double turning_share = 0.2;      // s
};

struct JointBlockedInput {
  double period_s = 0.0;
  std::array<double, 2> no_load_radps{};   // ν of the front (µ6) and rear (µ7) joint, (4.4)
  std::array<double, 2> velocity_radps{};  // w of the front and rear joint, measured
  bool driving = false;                    // the driver is in driving mode
};

class JointBlockedMonitor {
 public:
  // Throws std::invalid_argument unless T ≥ 0, ν_min > 0 and s in [0, 1), all finite.
  explicit JointBlockedMonitor(JointBlockedLimits limits = {});

  // One cycle. Returns the faults' texts ("front joint blocked: …", "rear joint blocked: …") of
  // the joints whose stall has lasted T in this cycle, front first; none in every other cycle.
  // Throws std::invalid_argument naming the input when one is not finite or h ≤ 0.
  std::vector<std::string> update(const JointBlockedInput& input);

  // How long each joint (front, rear) has been stalled without a break [s].
  const std::array<double, 2>& stalled_s() const { return stalled_s_; }

 private:
  JointBlockedLimits limits_;
  std::array<double, 2> stalled_s_{};
  // ∫|w| dt and ∫|ν| dt over each stall, for the fault's text (the share, the mean command).
  std::array<double, 2> turned_sum_{};
  std::array<double, 2> command_sum_{};
};

}  // namespace marsokhod::estimation
