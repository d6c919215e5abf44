#include "core/estimation/pose_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/checks/checks.hpp"

namespace marsokhod::estimation {
namespace {

using Matrix3 = std::array<double, 9>;

double at(const Matrix3& m, int r, int c) { return m[static_cast<std::size_t>(r * 3 + c)]; }

Matrix3 multiply(const Matrix3& a, const Matrix3& b) {
  Matrix3 out{};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      double sum = 0.0;
      for (int k = 0; k < 3; ++k) sum += at(a, r, k) * at(b, k, c);
      out[static_cast<std::size_t>(r * 3 + c)] = sum;
    }
  }
  return out;
}

Matrix3 transpose(const Matrix3& m) {
  Matrix3 out{};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out[static_cast<std::size_t>(c * 3 + r)] = at(m, r, c);
  }
  return out;
}

}  // namespace

double Pose::position_sigma_m() const { return std::sqrt(covariance[0] + covariance[4]); }
double Pose::heading_sigma_rad() const { return std::sqrt(covariance[8]); }

PoseEstimator::PoseEstimator(double wheel_radius_m, PoseNoise noise)
    : wheel_radius_m_(wheel_radius_m), noise_(noise) {
  if (!(std::isfinite(wheel_radius_m) && wheel_radius_m > 0.0)) {
    throw std::invalid_argument("PoseEstimator: the wheel radius must be > 0 m, got " +
                                std::to_string(wheel_radius_m));
  }
  for (const double n : {noise.distance_share, noise.gyro_rate_radps, noise.gyro_scale_share}) {
    if (!(std::isfinite(n) && n >= 0.0)) {
      throw std::invalid_argument("PoseEstimator: every noise term must be finite and ≥ 0, got " +
                                  std::to_string(n));
    }
  }
}

void PoseEstimator::reset() {
  pose_ = Pose{};
  last_angles_rad_.reset();
}

void PoseEstimator::correct(double heading_rad, double x_m, double y_m) {
  constexpr std::string_view kLaw = "PoseEstimator::correct";
  checks::law::require_finite(heading_rad, kLaw, "heading_rad");
  checks::law::require_finite(x_m, kLaw, "x_m");
  checks::law::require_finite(y_m, kLaw, "y_m");
  pose_.heading_rad += heading_rad;
  pose_.x_m += x_m;
  pose_.y_m += y_m;
}

const Pose& PoseEstimator::update(const OdometryInput& in) {
  constexpr std::string_view kLaw = "PoseEstimator::update";
  checks::law::require_finite(in.period_s, kLaw, "period_s");
  checks::law::require_finite(in.yaw_rate_radps, kLaw, "yaw_rate_radps");
  checks::law::require_finite(in.slope_rad, kLaw, "slope_rad");
  checks::law::require_finite(in.pitch_rad, kLaw, "pitch_rad");
  checks::law::require_finite(in.left_angle_rad, kLaw, "left_angle_rad");
  checks::law::require_finite(in.right_angle_rad, kLaw, "right_angle_rad");
  checks::law::require_finite(in.left_load_radps, kLaw, "left_load_radps");
  checks::law::require_finite(in.right_load_radps, kLaw, "right_load_radps");
  checks::law::require_finite(in.left_no_load_radps, kLaw, "left_no_load_radps");
  checks::law::require_finite(in.right_no_load_radps, kLaw, "right_no_load_radps");
  if (!(in.period_s > 0.0)) {
    throw std::invalid_argument("PoseEstimator::update: period_s must be > 0, got " +
                                std::to_string(in.period_s));
  }
  const double h = in.period_s;
  const std::array<double, 3> angles{in.pitch_rad, in.left_angle_rad, in.right_angle_rad};
  const std::array<double, 3> last = last_angles_rad_.value_or(angles);
  last_angles_rad_ = angles;
  const double wheels = 0.5 * ((angles[1] - last[1]) + (angles[2] - last[2]));
  const double ds = wheel_radius_m_ * (wheels + angles[0] - last[0]) * std::cos(in.slope_rad);
  const double dpsi = in.yaw_rate_radps * h;
  const double mid = pose_.heading_rad + 0.5 * dpsi;
  const double c = std::cos(mid);
  const double s = std::sin(mid);

  const double commanded = std::abs(in.left_no_load_radps) + std::abs(in.right_no_load_radps);
  const double loads = std::abs(in.left_load_radps) + std::abs(in.right_load_radps);
  const double slip = commanded > 0.0 ? std::min(1.0, loads / commanded) : 0.0;
  const double qs = noise_.distance_share * noise_.distance_share * std::abs(ds) * (1.0 + slip);
  const double qpsi = noise_.gyro_rate_radps * noise_.gyro_rate_radps * h +
                      noise_.gyro_scale_share * noise_.gyro_scale_share * std::abs(dpsi);
  const Matrix3 f{1.0, 0.0, -ds * s, 0.0, 1.0, ds * c, 0.0, 0.0, 1.0};
  Matrix3 p = multiply(multiply(f, pose_.covariance), transpose(f));
  // G Q Gᵀ with G = [c 0; s 0; 0 1], Q = diag(σ_s², σ_ψ²).
  p[0] += c * c * qs;
  p[1] += c * s * qs;
  p[3] += c * s * qs;
  p[4] += s * s * qs;
  p[8] += qpsi;

  pose_.x_m += ds * c;
  pose_.y_m += ds * s;
  pose_.heading_rad += dpsi;
  pose_.speed_mps = ds / h;
  pose_.yaw_rate_radps = in.yaw_rate_radps;
  pose_.distance_m += std::abs(ds);
  pose_.covariance = p;
  return pose_;
}

}  // namespace marsokhod::estimation
