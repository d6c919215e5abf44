// Where the rover is: a planar pose (x, y, ψ) in the odometry frame, dead-reckoned every cycle
// from the gyro and the centre axle's wheels, with its uncertainty (an extended Kalman filter's
// prediction step; there is no absolute measurement to correct it with).
//
// The frame: x forward and y to the left of the rover where the driver's start-up ended (or reset),
// ψ counter-clockwise seen from above, the same sense as the yaw rate of µ8's gyro. The point
// tracked is the middle of the centre axle: it is the chassis segment both joints hang from, and
// its two wheels are the only ones whose rolling is the chassis' motion in every elementary
// motion (the exterior axles move relative to it while a joint bends, (5.1)/(5.2)).
//
// Per cycle of period h, with the yaw rate ω (the gyro less its null (3.4)), the centre wheels'
// angles p̄_CL, p̄_CR from their encoders (chapter 3.2), the centre unit's pitch θ (+ nose down,
// the accelerometer's mean gravity, failsafes.hpp) and the wheel radius r, Δ the change since
// the last cycle:
//   Δs = r·((Δp̄_CL + Δp̄_CR)/2 + Δθ) · cos σ     the distance along the ground, projected to
//                                          the horizontal with the slope σ of chapter 6.2.1
// The encoders' angles, not the velocities w of chapter 4.2 (a windowed estimate that lags
// where the wheels reverse, as in wheel walking): the Δ add up to the angle turned, as
// diff_drive_controller's position feedback does. Δθ: the encoders count the wheels' turn
// against the centre unit, and when the unit pitches (a joint bending in wheel walking:
// ±0.1 rad in rolking) the wheels turn over the ground by that as well. The Δθ add up to the
// pitch's change since the pose began, so the accelerometer's noise does not gather.
//   Δψ = ω·h
//   x ← x + Δs·cos(ψ + Δψ/2),  y ← y + Δs·sin(ψ + Δψ/2),  ψ ← ψ + Δψ          (midpoint rule)
// The gyro null's drift over a leg in motion is taken back out of ψ when the rover stands again
// and the position's drift with it (correct, null_drift.hpp: a zero-velocity update).
// Skid steering turns the rover by dragging wheels sideways, so the wheels' difference says
// little about the heading (the thesis: odometry "meaningless … in particular when the robot is
// turning"); the gyro gives it. The wheels give the distance only where they roll.
//
// Uncertainty, P the 3×3 covariance of (x, y, ψ):
//   P ← F P Fᵀ + G Q Gᵀ,  F = [1 0 −Δs·sin ψ̄; 0 1 Δs·cos ψ̄; 0 0 1],  G = [cos ψ̄ 0; sin ψ̄ 0; 0 1]
//   Q = diag(σ_s², σ_ψ²),  σ_s² = k_s²·|Δs|·(1 m)·(1 + slip),  σ_ψ² = σ_ω²·h + k_ψ²·|Δψ|·(1 rad)
// with ψ̄ = ψ + Δψ/2. Both are random walks: the distance's σ after 1 m of rolling is k_s, the
// heading's after 1 s at rest σ_ω and after one radian turned k_ψ; the covariance does not depend
// on the cycle's period. slip = min(1, (|l_CL| + |l_CR|)/(|ν_CL| + |ν_CR|)) is the centre wheels'
// load (Definition 4.9) against their commanded speed: a wheel that slips or is blocked meets a
// load as large as its command, and its distance then counts twice in P. A scale error that
// stays (the wheel radius: 0.125 m with the blades on solid ground, 0.115 m on granules) grows
// with the distance, not its square root; P does not model it.
#pragma once

#include <array>
#include <optional>

namespace marsokhod::estimation {

struct PoseNoise {
  double distance_share = 0.02;       // k_s: σ 2 cm after 1 m on rolling wheels
  double gyro_rate_radps = 0.005;     // σ_ω [rad/√s]: the gyro's rate noise after its null
  double gyro_scale_share = 0.02;     // k_ψ: σ 0.02 rad after one radian turned
};

struct OdometryInput {
  double period_s = 0.0;                  // h
  double yaw_rate_radps = 0.0;            // ω, the gyro less its null (3.4)
  double slope_rad = 0.0;                 // σ of chapter 6.2.1
  double pitch_rad = 0.0;                 // θ of the centre unit, + nose down
  double left_angle_rad = 0.0;            // p̄_CL, the encoder's wheel angle
  double right_angle_rad = 0.0;           // p̄_CR
  double left_load_radps = 0.0;           // l_CL = w − ν (Definition 4.9)
  double right_load_radps = 0.0;          // l_CR
  double left_no_load_radps = 0.0;        // ν_CL of (4.4)
  double right_no_load_radps = 0.0;       // ν_CR
};

struct Pose {
  double x_m = 0.0;
  double y_m = 0.0;
  double heading_rad = 0.0;          // ψ, unwrapped (turns add up)
  double speed_mps = 0.0;            // Δs/h, signed (backward < 0)
  double yaw_rate_radps = 0.0;       // ω
  double distance_m = 0.0;           // Σ|Δs|: the path length
  std::array<double, 9> covariance{};  // P, row-major, (x, y, ψ)
  double position_sigma_m() const;   // √(P_xx + P_yy)
  double heading_sigma_rad() const;  // √P_ψψ
};

class PoseEstimator {
 public:
  // Throws std::invalid_argument unless the wheel radius is > 0 and every noise term ≥ 0, all
  // finite.
  PoseEstimator(double wheel_radius_m, PoseNoise noise = {});

  // One cycle. Throws std::invalid_argument naming the field when an input is not finite or
  // h ≤ 0; the pose is unchanged then.
  const Pose& update(const OdometryInput& input);

  // Back to the origin with no uncertainty: the odometry frame starts here.
  void reset();

  // Adds Δψ to the heading and (Δx, Δy) to the position: the gyro null's drift over the last
  // leg and where it took the dead reckoning, measured when the rover stands again
  // (null_drift.hpp). Throws std::invalid_argument on a non-finite argument; the pose is
  // unchanged then.
  void correct(double heading_rad, double x_m, double y_m);

  const Pose& pose() const { return pose_; }

 private:
  double wheel_radius_m_;
  PoseNoise noise_;
  Pose pose_;
  // θ, p̄_CL, p̄_CR of the last update (none yet: no change).
  std::optional<std::array<double, 3>> last_angles_rad_;
};

}  // namespace marsokhod::estimation
