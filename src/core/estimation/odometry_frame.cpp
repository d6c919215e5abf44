#include "core/estimation/odometry_frame.hpp"

#include <cmath>
#include <numbers>

namespace marsokhod::estimation {

PlanarPose to_frame(const PlanarPose& origin, const PlanarPose& outer) {
  const double c = std::cos(origin.heading_rad);
  const double s = std::sin(origin.heading_rad);
  const double dx = outer.x_m - origin.x_m;
  const double dy = outer.y_m - origin.y_m;
  return {c * dx + s * dy, -s * dx + c * dy, outer.heading_rad - origin.heading_rad};
}

PlanarPose from_frame(const PlanarPose& origin, const PlanarPose& local) {
  const double c = std::cos(origin.heading_rad);
  const double s = std::sin(origin.heading_rad);
  return {origin.x_m + c * local.x_m - s * local.y_m, origin.y_m + s * local.x_m + c * local.y_m,
          origin.heading_rad + local.heading_rad};
}

void OdometryFrameTracker::observe(double x_m, double y_m, double yaw_rad, bool new_frame) {
  if (!started_) {
    last_ = {x_m, y_m, yaw_rad};
  } else {
    last_.x_m = x_m;
    last_.y_m = y_m;
    last_.heading_rad += std::remainder(yaw_rad - last_raw_yaw_rad_, 2.0 * std::numbers::pi);
  }
  last_raw_yaw_rad_ = yaw_rad;
  if (new_frame || !started_) origin_ = last_;
  started_ = true;
}

PlanarPose OdometryFrameTracker::pose() const { return to_frame(origin_, last_); }

}  // namespace marsokhod::estimation
