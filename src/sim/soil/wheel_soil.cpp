#include "sim/soil/wheel_soil.hpp"

#include <algorithm>
#include <optional>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "sim/soil/angle_steps.hpp"
#include "sim/soil/wide.hpp"

namespace marsokhod::sim::soil {
namespace {

double mobilised(double displacement_m, double shear_modulus_m) {
  const double share = 1.0 - std::exp(-std::abs(displacement_m) / shear_modulus_m);
  return displacement_m < 0.0 ? -share : share;
}

// The unloading branch of sheared(), out of line: the loading branch, nearly every sample's, is
// an addition and inlines into the advection's loop.
[[gnu::noinline]] double unloaded(double j, double dj, double inverse_K, double ratio) {
  const double remaining = exp_nonpositive(-std::abs(j) * inverse_K);  // 1 − share
  const double unload = (1.0 - remaining) / (ratio * inverse_K);
  const double d = std::abs(dj);
  if (d >= unload) return std::copysign(d - unload, dj);
  const double loaded = remaining + ratio * d * inverse_K;  // in (0, 1]: d < unload
  const double a =
      -(loaded >= std::numeric_limits<double>::min() ? log_positive(loaded) : std::log(loaded)) /
      inverse_K;
  return std::copysign(a, j);
}

// One step of shear displacement dj on soil displaced j. Loading (dj along j, or from j = 0)
// follows Janosi–Hanamoto's curve; unloading (dj against j) is stiffer, ratio/K in the mobilised
// share per metre, until the share reaches 0, and the rest of the step loads the other way.
inline double sheared(double j, double dj, double inverse_K, double ratio) {
  if (dj == 0.0 || j == 0.0 || (j > 0.0) == (dj > 0.0)) return j + dj;
  return unloaded(j, dj, inverse_K, ratio);
}

// sheared() with the memory of the displacement `peak` at which the soil last began to unload:
// loading again below it, the soil reloads along the stiff line it unloaded on (ratio/K in the
// mobilised share per metre) until it is back at the peak, and from there follows
// Janosi–Hanamoto's curve again. Unloading through 0 forgets the peak.
[[gnu::noinline]] double reloaded(double j, double& peak, double dj, double inverse_K,
                                  double ratio) {
  if (dj == 0.0) return j;
  if (j == 0.0 ? (peak > 0.0) == (dj > 0.0) : (j > 0.0) == (dj > 0.0)) {  // loading
    if (peak == 0.0 || (peak > 0.0) != (dj > 0.0) || std::abs(j) >= std::abs(peak)) {
      peak = 0.0;
      return j + dj;
    }
    const double remaining = exp_nonpositive(-std::abs(j) * inverse_K);
    const double at_peak = exp_nonpositive(-std::abs(peak) * inverse_K);
    const double to_peak = (remaining - at_peak) / (ratio * inverse_K);
    const double d = std::abs(dj);
    if (d >= to_peak) {
      const double beyond = peak + std::copysign(d - to_peak, dj);
      peak = 0.0;
      return beyond;
    }
    return std::copysign(-log_positive(remaining - ratio * d * inverse_K) / inverse_K, dj);
  }
  if (j == 0.0) {  // no displacement and no peak this way: loads
    peak = 0.0;
    return dj;
  }
  if (peak == 0.0 || (peak > 0.0) != (j > 0.0) || std::abs(peak) < std::abs(j)) peak = j;
  const double out = unloaded(j, dj, inverse_K, ratio);
  if (out == 0.0 || (out > 0.0) != (j > 0.0)) peak = 0.0;
  return out;
}

}  // namespace

// The motion frame in world coordinates: x along the direction the arc lies in, y the axle,
// z the wheel's up in its own plane.
struct WheelSoilContact::Frame {
  Vec3 forward, axle, up;
  double spin_radps, travel_mps, lateral_mps, slip;
  int handedness;
};

WheelSoilContact::WheelSoilContact(SoilParams soil, WheelGeometry wheel)
    : soil_(std::move(soil)), wheel_(wheel) {
  validate(soil_);
  validate(wheel_);
  strength_ = shear_strength(soil_);
  blades_ = blade_axes(wheel_);
  modulus_pa_ = soil_.cohesive_modulus / wheel_.width_m + soil_.frictional_modulus;
  passive_ = passive_earth_coefficient(soil_);
  const auto size = static_cast<std::size_t>(wheel_.lanes * wheel_.arc_samples);
  shear_t_.assign(size, 0.0);
  shear_y_.assign(size, 0.0);
  peak_t_.assign(size, 0.0);
  cosines_.assign(static_cast<std::size_t>(wheel_.arc_samples), 0.0);
  sample_sin_.assign(static_cast<std::size_t>(wheel_.arc_samples), 0.0);
  sample_cos_.assign(static_cast<std::size_t>(wheel_.arc_samples), 0.0);
  sample_sigma_.assign(static_cast<std::size_t>(wheel_.arc_samples), 0.0);
  share_across_.assign(static_cast<std::size_t>(wheel_.arc_samples), 0.0);
  share_along_.assign(static_cast<std::size_t>(wheel_.arc_samples), 0.0);
  unloading_.assign(2 * static_cast<std::size_t>(wheel_.arc_samples), 0);
}

double WheelSoilContact::lane_offset_m(int lane) const {
  return ((lane + 0.5) / wheel_.lanes - 0.5) * wheel_.width_m;
}

void WheelSoilContact::update_direction(double rim_speed_mps, double travel_speed_mps,
                                        double dt_s) {
  const double lead = direction_ * (rim_speed_mps + travel_speed_mps) * dt_s;
  retreat_m_ = std::max(retreat_m_ - lead, 0.0);
  if (retreat_m_ <= soil_.shear_modulus_m) return;
  direction_ = -direction_;
  retreat_m_ = 0.0;
  const int samples = wheel_.arc_samples;
  for (int lane = 0; lane < wheel_.lanes; ++lane) {
    double* jt = shear_t_.data() + lane * samples;
    double* jy = shear_y_.data() + lane * samples;
    double* peak = peak_t_.data() + lane * samples;
    std::reverse(jt, jt + samples);
    std::reverse(jy, jy + samples);
    std::reverse(peak, peak + samples);
    for (int k = 0; k < samples; ++k) {
      jt[k] = -jt[k];
      peak[k] = -peak[k];
    }
  }
}

// Semi-Lagrangian transport of the lane's displacement along the arc, then the step's slip.
void WheelSoilContact::advect_lane(int lane, const ContactArc& arc, double spin_radps,
                                   double travel_mps, double lateral_mps, double dt_s) {
  const int samples = wheel_.arc_samples;
  const double span = arc.front_rad - arc.exit_rad;
  const double shift = std::max(spin_radps, 0.0) * dt_s / span * samples;  // in samples
  const double rs = wheel_.shear_radius_m();
  const double spacing = 1.0 / samples;
  // The slip rate at the middle of the path since the last step, at least half a sample
  // upstream: the linear interpolation's steady state then sums it by the midpoint rule. That
  // middle lies (k + ½)/2 samples from the entry for the first ⌈reach − ½⌉ samples, k + ½ − reach/2
  // beyond (reach = max(shift, 1)): θ is linear in k on either side, so its cosines come by
  // rotation (angle_steps.hpp).
  const double reach = std::max(shift, 1.0);
  const int near = std::clamp(static_cast<int>(std::ceil(reach - 0.5)), 0, samples);
  if (near == 1) {  // the usual case, one sample: its cosine alone
    cosines_[0] = sin_cos(arc.front_rad - 0.25 * spacing * span).cos;
  } else if (near > 1) {
    AngleSteps angle(arc.front_rad - 0.25 * spacing * span, -0.5 * spacing * span);
    for (int k = 0; k < near; ++k, angle.advance()) {
      cosines_[static_cast<std::size_t>(k)] = angle.cos();
    }
  }
  if (near < samples) {
    AngleSteps angle(arc.front_rad - (near + 0.5 - 0.5 * reach) * spacing * span, -spacing * span);
    for (int k = near; k < samples; ++k, angle.advance()) {
      cosines_[static_cast<std::size_t>(k)] = angle.cos();
    }
  }
  // Both components move with the rim: the same interpolation for each. The rim moved `whole`
  // samples and a fraction: sample k takes (1 − fraction)·j[k − whole] + fraction·j[k − whole − 1]
  // while k − shift > 0, a ramp from the entry (j = 0 at −0.5) within half a sample of it, else 0.
  // In place from the exit back: a sample reads only samples before it, or itself.
  double* jt = shear_t_.data() + lane * samples;
  double* jy = shear_y_.data() + lane * samples;
  const double lateral_step = -lateral_mps * dt_s;
  const double spin_term = rs * spin_radps;
  const int whole = static_cast<int>(std::min(shift, static_cast<double>(samples)));
  const double fraction = shift - whole;
  const int first = std::min(whole + 1, samples);  // the first sample fed from within the arc
  const double inverse_K = strength_.inverse_shear_modulus_per_m;
  const double ratio = soil_.unloading_stiffness_ratio;
  // With the reload memory the tangential state goes through reloaded(), its peak moved with it.
  double* peak = soil_.tangential_reload_memory ? peak_t_.data() + lane * samples : nullptr;
  const auto shear_t = [&](double j, double& p, double dj) {
    return peak != nullptr ? reloaded(j, p, dj, inverse_K, ratio)
                           : sheared(j, dj, inverse_K, ratio);
  };
  double no_peak = 0.0;  // the peak slot without the memory (never read)
  // Four at a time first where AVX2 is, while the samples load (the same bits), the rest one by
  // one.
  int last = samples - 1;
  if (wide::available()) {
    int unloading = 0;
    last = wide::advect_loading(jt, jy, peak, cosines_.data(), samples, first, whole, fraction,
                                spin_term, travel_mps, dt_s, lateral_step, unloading_.data(),
                                unloading);
    for (int i = 0; i < unloading; ++i) {
      const int k = unloading_[static_cast<std::size_t>(i)] / 2;
      if (unloading_[static_cast<std::size_t>(i)] % 2 == 0) {
        const double cosine = cosines_[static_cast<std::size_t>(k)];
        jt[k] = shear_t(jt[k], peak != nullptr ? peak[k] : no_peak,
                        (spin_term - travel_mps * cosine) * dt_s);
      } else {
        jy[k] = sheared(jy[k], lateral_step, inverse_K, ratio);
      }
    }
  }
  for (int k = last; k >= first; --k) {
    const int at = k - whole;
    const double value_t = (1.0 - fraction) * jt[at] + fraction * jt[at - 1];
    const double value_y = (1.0 - fraction) * jy[at] + fraction * jy[at - 1];
    double& value_p = peak != nullptr ? peak[k] : no_peak;
    if (peak != nullptr) value_p = (1.0 - fraction) * peak[at] + fraction * peak[at - 1];
    jt[k] = shear_t(value_t, value_p,
                    (spin_term - travel_mps * cosines_[static_cast<std::size_t>(k)]) * dt_s);
    jy[k] = sheared(value_y, lateral_step, inverse_K, ratio);
  }
  const double entry_t = jt[0], entry_y = jy[0], entry_p = peak != nullptr ? peak[0] : 0.0;
  for (int k = first - 1; k >= 0; --k) {
    const double from = k - shift;  // in (−0.5, 0]: on the ramp from the entry
    const double ramp = from > -0.5 ? (from + 0.5) / 0.5 : 0.0;
    const double cosine = cosines_[static_cast<std::size_t>(k)];
    double& value_p = peak != nullptr ? peak[k] : no_peak;
    if (peak != nullptr) value_p = entry_p * ramp;
    jt[k] = shear_t(entry_t * ramp, value_p, (spin_term - travel_mps * cosine) * dt_s);
    jy[k] = sheared(entry_y * ramp, lateral_step, inverse_K, ratio);
  }
}

// Per sample of width Δb = b/lanes and angle Δθ, with outward = sin θ·x − cos θ·z and
// tangent = cos θ·x + sin θ·z in the motion frame (x, y, z):
//   normal force −σ r ΔθΔb·outward, shear (τ_t tangent + τ_y y) r_s ΔθΔb,
// summed as scalars in (x, y, z). About the lane's centre the normal force has no moment, and
// outward × tangent = −d·y, outward × y = d·(cos θ·x + sin θ·z), d = ±1 the motion frame's
// direction (x × y = d·z): the moments are summed as scalars too, the frame applied once.
void WheelSoilContact::add_lane_stresses(int lane, const ContactArc& arc, const Frame& frame,
                                         WheelWrench& wrench) {
  const int samples = wheel_.arc_samples;
  const double r = wheel_.rim_radius_m, rs = wheel_.shear_radius_m();
  const double step = (arc.front_rad - arc.exit_rad) / samples;
  const double area = step * wheel_.width_m / wheel_.lanes;
  const bool compressed = arc.max_stress_rad > arc.exit_rad;  // a rear part mapped onto the front
  const double rear_rate =
      compressed ? step * (arc.front_rad - arc.max_stress_rad) / (arc.max_stress_rad - arc.exit_rad)
                 : 0.0;
  const std::size_t base = static_cast<std::size_t>(lane * samples);
  // First the angles and the normal stresses (independent from sample to sample, so their
  // exponentials overlap), then the shear and the sums.
  double* sines = sample_sin_.data();
  double* cosines = sample_cos_.data();
  double* sigmas = sample_sigma_.data();
  {
    AngleSteps angle(arc.front_rad - 0.5 * step, -step);
    std::optional<AngleSteps> rear;  // θ* behind θm
    for (int k = 0; k < samples; ++k, angle.advance()) {
      const double theta = arc.front_rad - (k + 0.5) * step;
      sines[k] = angle.sin();
      cosines[k] = angle.cos();
      double cos_equivalent = angle.cos();
      if (compressed && theta < arc.max_stress_rad) {
        if (!rear) rear.emplace(equivalent_angle_rad(arc, theta), rear_rate);
        cos_equivalent = rear->cos();
        rear->advance();
      }
      sigmas[k] = cos_equivalent;
    }
    normal_stresses_from_cos_pa(modulus_pa_, arc, r, sigmas, samples);
  }
  // Then the blades' mobilised shares (the exponentials again in a loop of their own).
  const BladeFrame blade = blade_frame(blades_, frame.handedness);
  double* across = share_across_.data();
  double* along = share_along_.data();
  if (blades_.bladed) {
    const double inverse_K = strength_.inverse_shear_modulus_per_m;
    // Four at a time first where AVX2 is (the same bits), the rest two at a time.
    const int four_wide =
        wide::available()
            ? wide::blade_shares(shear_t_.data() + base, shear_y_.data() + base, samples,
                                 blade.across_t, blade.across_y, blade.along_t, blade.along_y,
                                 inverse_K, across, along)
            : 0;
    for (int k = four_wide; k < samples; ++k) {
      const double jt = shear_t_[base + k], jy = shear_y_[base + k];
      const DoublePair shares = detail::mobilised(
          DoublePair{blade.across_displacement_m(jt, jy), blade.along_displacement_m(jt, jy)},
          inverse_K);
      across[k] = shares[0];
      along[k] = shares[1];
    }
  }
  double fx = 0.0, fy = 0.0, fz = 0.0, mx = 0.0, my = 0.0, mz = 0.0;
  int k = 0;
  if (blades_.bladed) {
    // Four sums of each, over every fourth sample (four-wide where AVX2 is, the same operations
    // one by one elsewhere: the same bits), then added pairwise; the rest below.
    const wide::BladedSample sample{strength_.cohesion_pa, strength_.tan_friction,
                                    strength_.tan_metal_friction, blade.across_t, blade.across_y,
                                    blade.along_t, blade.along_y, r, rs, area};
    wide::BladedSums sums{};
    const int grouped = samples - samples % 4;
    if (wide::available()) {
      wide::bladed_sums(sample, sines, cosines, sigmas, across, along, samples, sums);
    } else {
      for (int i = 0; i < grouped; ++i) {
        const auto j = static_cast<std::size_t>(i % 4);
        const double s = sines[i], c = cosines[i], sigma = sigmas[i];
        const SurfaceShear tau = bladed_shear(strength_, blade, sigma, across[i], along[i]);
        const double normal = sigma * r * area, tangential = tau.tangential_pa * rs * area;
        const double lateral = tau.lateral_pa * rs * area;
        sums.fx[j] += tangential * c - normal * s;
        sums.fz[j] += normal * c + tangential * s;
        sums.fy[j] += lateral;
        sums.my[j] -= tangential * rs;
        sums.mx[j] += lateral * rs * c;
        sums.mz[j] += lateral * rs * s;
      }
    }
    const auto pairwise = [](const double (&lanes)[4]) {
      return (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]);
    };
    fx = pairwise(sums.fx);
    fy = pairwise(sums.fy);
    fz = pairwise(sums.fz);
    mx = pairwise(sums.mx);
    my = pairwise(sums.my);
    mz = pairwise(sums.mz);
    k = grouped;
  }
  for (; k < samples; ++k) {
    const double s = sines[k], c = cosines[k], sigma = sigmas[k];
    const SurfaceShear tau =
        blades_.bladed ? bladed_shear(strength_, blade, sigma, across[k], along[k])
                       : rim_shear(strength_, blades_, frame.handedness, sigma,
                                   shear_t_[base + k], shear_y_[base + k]);
    const double normal = sigma * r * area, tangential = tau.tangential_pa * rs * area;
    const double lateral = tau.lateral_pa * rs * area;
    fx += tangential * c - normal * s;
    fz += normal * c + tangential * s;
    fy += lateral;
    my -= tangential * rs;
    mx += lateral * rs * c;
    mz += lateral * rs * s;
  }
  const double d = direction_;
  const Vec3 force = fx * frame.forward + fy * frame.axle + fz * frame.up;
  wrench.force_n += force;
  wrench.torque_nm += cross(lane_offset_m(lane) * frame.axle, force);
  wrench.torque_nm += (d * mx) * frame.forward + (d * my) * frame.axle + (d * mz) * frame.up;
}

void WheelSoilContact::add_damping(double contact_area_m2, const Frame& frame,
                                   const Vec3& velocity_mps, WheelWrench& wrench) const {
  const double normal = dot(wrench.force_n, frame.up);
  double damping =
      -soil_.vertical_damping_pa_s_per_m * contact_area_m2 * dot(velocity_mps, frame.up);
  damping = std::max(damping, -std::max(normal, 0.0));  // never sucks the wheel in
  wrench.force_n += damping * frame.up;
}

void WheelSoilContact::add_sidewall(std::span<const double> lane_sinkage_m, const Frame& frame,
                                    WheelWrench& wrench) const {
  double mean = 0.0;
  int count = 0;
  const int samples = wheel_.arc_samples;
  for (int lane = 0; lane < wheel_.lanes; ++lane) {
    if (lane_sinkage_m[static_cast<std::size_t>(lane)] <= 0.0) continue;
    for (int k = 0; k < samples; ++k)
      mean += shear_y_[static_cast<std::size_t>(lane * samples + k)];
    count += samples;
  }
  if (count == 0) return;
  mean /= count;
  // The face that moves into the soil: the wheel pulled toward −y (j_y > 0) pushes with its −y
  // side.
  const int leading = mean > 0.0 ? 0 : wheel_.lanes - 1;
  const double sinkage = lane_sinkage_m[static_cast<std::size_t>(leading)];
  const double force = sidewall_resistance_n(soil_, passive_, wheel_.rim_radius_m, sinkage) *
                       mobilised(mean, soil_.shear_modulus_m);
  const double side = mean > 0.0 ? -0.5 : 0.5;
  const Vec3 at = (side * wheel_.width_m) * frame.axle -
                  (wheel_.rim_radius_m - 0.5 * std::max(sinkage, 0.0)) * frame.up;
  const Vec3 push = force * frame.axle;
  wrench.force_n += push;
  wrench.torque_nm += cross(at, push);
  wrench.diagnostics.sidewall_n = force;
}

WheelSoilContact::Frame WheelSoilContact::motion_frame(const WheelKinematics& kinematics,
                                                       const Vec3& forward_wheel,
                                                       double travel_mps) const {
  Frame frame;
  frame.forward = static_cast<double>(direction_) * forward_wheel;
  frame.axle = kinematics.axle;
  frame.up = cross(forward_wheel, kinematics.axle);
  frame.spin_radps = direction_ * kinematics.spin_radps;
  frame.travel_mps = direction_ * travel_mps;
  frame.lateral_mps = dot(kinematics.velocity_mps, kinematics.axle);
  frame.slip = regularised_slip(wheel_.shear_radius_m() * frame.spin_radps, frame.travel_mps);
  frame.handedness = direction_ * static_cast<int>(wheel_.handedness);
  return frame;
}

WheelWrench WheelSoilContact::step(const WheelKinematics& kinematics, const Vec3& ground_normal,
                                   std::span<const double> lane_sinkage_m,
                                   std::span<const double> lane_exit_rad,
                                   std::span<const double> lane_front_rad,
                                   std::span<const double> lane_entry_rad, double dt_s) {
  const auto lanes = static_cast<std::size_t>(wheel_.lanes);
  if (lane_sinkage_m.size() != lanes || (!lane_exit_rad.empty() && lane_exit_rad.size() != lanes) ||
      (!lane_front_rad.empty() && lane_front_rad.size() != lanes) ||
      (!lane_entry_rad.empty() && lane_entry_rad.size() != lanes) || !(dt_s >= 0.0) ||
      !std::isfinite(dt_s)) {
    std::ostringstream message;
    message << "WheelSoilContact::step: expected " << wheel_.lanes
            << " lane sinkages (and as many exit, front and entry angles, or none) and a finite"
            << " dt_s >= 0, got " << lane_sinkage_m.size() << ", " << lane_exit_rad.size() << ", "
            << lane_front_rad.size() << ", " << lane_entry_rad.size() << " and " << dt_s;
    throw std::invalid_argument(message.str());
  }
  const Vec3 rolling = cross(kinematics.axle, ground_normal);
  const double length = norm(rolling);
  WheelWrench wrench;
  if (length < 1e-9) return wrench;  // the axle stands on its end: no rolling contact
  const Vec3 forward_wheel = (1.0 / length) * rolling;
  const double rim_speed = wheel_.shear_radius_m() * kinematics.spin_radps;
  const double travel = dot(kinematics.velocity_mps, forward_wheel);
  const int given_direction = direction_;  // the frame the exit and front angles were found in
  update_direction(rim_speed, travel, dt_s);
  const bool mirrored = direction_ != given_direction;
  const Frame frame = motion_frame(kinematics, forward_wheel, travel);
  double contact_area = 0.0;
  for (int lane = 0; lane < wheel_.lanes; ++lane) {
    const double sinkage = lane_sinkage_m[static_cast<std::size_t>(lane)];
    double exit = lane_exit_rad.empty() ? 0.0 : lane_exit_rad[static_cast<std::size_t>(lane)];
    double front = lane_front_rad.empty() ? std::numeric_limits<double>::infinity()
                                          : lane_front_rad[static_cast<std::size_t>(lane)];
    if (mirrored && !lane_exit_rad.empty() && !lane_front_rad.empty()) {
      // Found in the frame this step turned: what lay behind now lies ahead.
      const double behind = exit;
      exit = -front;
      front = -behind;
    }
    const ContactArc arc =
        lane_entry_rad.empty()
            ? contact_arc(soil_, wheel_.rim_radius_m, sinkage, frame.slip, exit, front)
            : contact_arc_at_entry(soil_, wheel_.rim_radius_m, sinkage, frame.slip, exit, front,
                                   lane_entry_rad[static_cast<std::size_t>(lane)]);
    if (!(sinkage > 0.0) || !(arc.front_rad > arc.exit_rad)) {
      // Released: the soil the rim left keeps no displacement.
      const auto first = static_cast<std::ptrdiff_t>(lane * wheel_.arc_samples);
      std::fill(shear_t_.begin() + first, shear_t_.begin() + first + wheel_.arc_samples, 0.0);
      std::fill(shear_y_.begin() + first, shear_y_.begin() + first + wheel_.arc_samples, 0.0);
      std::fill(peak_t_.begin() + first, peak_t_.begin() + first + wheel_.arc_samples, 0.0);
      continue;
    }
    advect_lane(lane, arc, frame.spin_radps, frame.travel_mps, frame.lateral_mps, dt_s);
    add_lane_stresses(lane, arc, frame, wrench);
    contact_area +=
        (arc.front_rad - arc.exit_rad) * wheel_.rim_radius_m * wheel_.width_m / wheel_.lanes;
    wrench.sinkage_m = std::max(wrench.sinkage_m, std::min(sinkage, wheel_.rim_radius_m));
    wrench.diagnostics.entry_angle_rad =
        std::max(wrench.diagnostics.entry_angle_rad, arc.entry_rad);
    wrench.diagnostics.in_contact = true;
  }
  if (wrench.diagnostics.in_contact) {
    add_damping(contact_area, frame, kinematics.velocity_mps, wrench);
    add_sidewall(lane_sinkage_m, frame, wrench);
  }
  WheelDiagnostics& diagnostics = wrench.diagnostics;
  diagnostics.slip = direction_ * frame.slip;
  diagnostics.normal_load_n = dot(wrench.force_n, frame.up);
  diagnostics.drawbar_pull_n = dot(wrench.force_n, forward_wheel);
  diagnostics.lateral_n = dot(wrench.force_n, kinematics.axle);
  diagnostics.resisting_torque_nm = dot(wrench.torque_nm, kinematics.axle);
  return wrench;
}

}  // namespace marsokhod::sim::soil
