// The odometry frame of pose_estimator.hpp seen from outside: where the driver (re)started, x
// forward, y to the left, the heading counter-clockwise. A pose known in another planar frame (the
// simulator's world) is carried into it and back here, and OdometryFrameTracker follows one —
// the simulator's true pose — into the frame of the driver's latest (re)start, so that the
// truth can be set beside the dead-reckoned pose (the scenarios' odometry metrics, the console's
// map). Pure, no I/O.
//
// With the origin (x₀, y₀, ψ₀) in the outer frame and c = cos ψ₀, s = sin ψ₀:
//   to_frame:   x = c·(X − x₀) + s·(Y − y₀),  y = −s·(X − x₀) + c·(Y − y₀),  ψ = Ψ − ψ₀
//   from_frame: X = x₀ + c·x − s·y,           Y = y₀ + s·x + c·y,           Ψ = ψ₀ + ψ
// Headings are not wrapped: an unwrapped heading stays unwrapped.
#pragma once

namespace marsokhod::estimation {

struct PlanarPose {
  double x_m = 0.0;
  double y_m = 0.0;
  double heading_rad = 0.0;
};

// `outer` (a pose in the outer frame) expressed in the frame whose origin is `origin`.
PlanarPose to_frame(const PlanarPose& origin, const PlanarPose& outer);
// The inverse: `local` (in the frame at `origin`) expressed in the outer frame.
PlanarPose from_frame(const PlanarPose& origin, const PlanarPose& local);

// Follows a pose of the outer frame (each cycle's truth) in the odometry frame. The outer yaw may
// come in any range (−π..π from a rotation matrix): it is unwrapped here, cycle to cycle, so the
// heading adds up turns as the driver's does. A frame starts at the first observation and
// whenever the caller says so: while a (re)started driver's pose stays at zero (its start-up),
// so that the frame starts where the driver's does.
class OdometryFrameTracker {
 public:
  // One cycle's outer pose. `new_frame`: the frame starts here (this pose becomes its origin).
  void observe(double x_m, double y_m, double yaw_rad, bool new_frame);
  bool started() const { return started_; }
  // The pose of the last observation in the current frame (zero before any).
  PlanarPose pose() const;
  // The current frame's origin in the outer frame, its yaw unwrapped since the first observation.
  const PlanarPose& origin() const { return origin_; }

 private:
  bool started_ = false;
  PlanarPose origin_;
  PlanarPose last_;  // the outer pose, yaw unwrapped
  double last_raw_yaw_rad_ = 0.0;
};

}  // namespace marsokhod::estimation
