// An independent numeric integration of the Wong–Reece rigid-wheel equations, written apart from
// src/sim/soil (no shared code): composite Simpson on each side of the stress maximum θm, where the
// normal stress has its kink, and the closed-form shear displacement of a steadily slipping wheel.
//   σ(θ) = (k_c/b + k_φ) r^n (cos θ* − cos θ1)^n,  n = n0 + n1|s|,  θm = (c1 + c2 s) θ1
//   j(θ) = r_s (θ1 − θ) − (v/ω)(sin θ1 − sin θ),    v/ω = r_s(1 − s) (s ≥ 0), r_s/(1 + s) (s < 0)
//   blades (inclination i, handedness h): j_n = j cos i, j_b = j h sin i,
//     τ_t = (c + σ tan φ)(1 − e^(−|j_n|/K)) sgn(j_n) cos i + σ tan δ (1 − e^(−|j_b|/K)) sgn(j_b) h
//     sin i
//   W  = b ∫ (σ r cos θ + τ_t r_s sin θ) dθ,   DP = b ∫ (τ_t r_s cos θ − σ r sin θ) dθ
// With an unloading ratio R > 0 the mobilised shares 1 − e^(−|j|/K) follow each soil element's
// path from the entry instead (the elastoplastic shear of wheel_soil.hpp): m(θ) integrated down
// the arc in the share itself, loading toward ±1 as dm = (1 − |m|)·|dj|/K, unloading (dj against
// m) as dm = R·dj/K until m reaches 0, the rest of the step loading the other way. Where j grows
// monotonically from the entry (a driven wheel) the two agree.
#pragma once

#include <cmath>

namespace marsokhod::sim::soil::reference {

struct Soil {
  double n0, n1, kc, kphi, c, phi, K, delta, c1, c2;
  double unloading_ratio = 0.0;  // 0: Janosi–Hanamoto of the total displacement (Wong–Reece)
};
struct Wheel {
  double r, rs, b, inclination;
  int handedness;
  bool bladed;
};
struct Result {
  double weight_n, drawbar_pull_n, sinkage_m;
};

inline double sgn(double x) { return x < 0.0 ? -1.0 : (x > 0.0 ? 1.0 : 0.0); }

// The shear displacement j(θ) of a steadily slipping wheel.
inline double displacement(const Wheel& w, double z, double s, double theta) {
  const double theta1 = std::acos(1.0 - z / w.r);
  const double v_over_omega = s >= 0.0 ? w.rs * (1.0 - s) : w.rs / (1.0 + s);
  return w.rs * (theta1 - theta) - v_over_omega * (std::sin(theta1) - std::sin(theta));
}

// One step dj of the elastoplastic share m (the header's law).
inline double share_step(double m, double dj, double K, double ratio) {
  if (dj == 0.0) return m;
  if (m == 0.0 || sgn(m) == sgn(dj)) {
    return sgn(dj) * (1.0 - (1.0 - std::fabs(m)) * std::exp(-std::fabs(dj) / K));
  }
  const double unloaded = m + ratio * dj / K;
  if (sgn(unloaded) == sgn(m)) return unloaded;
  const double rest = std::fabs(dj) - std::fabs(m) * K / ratio;
  return sgn(dj) * (1.0 - std::exp(-rest / K));
}

// The mobilised shares at θ: {across (or the smooth rim's), along the blades}. With shares given
// (the elastoplastic path), those; otherwise from j(θ).
struct Shares {
  double across, along;
};
inline Shares classic_shares(const Soil& soil, const Wheel& w, double z, double s, double theta) {
  const double j = displacement(w, z, s, theta);
  const double jn = w.bladed ? j * std::cos(w.inclination) : j;
  const double jb = w.bladed ? j * w.handedness * std::sin(w.inclination) : 0.0;
  return {(1.0 - std::exp(-std::fabs(jn) / soil.K)) * sgn(jn),
          (1.0 - std::exp(-std::fabs(jb) / soil.K)) * sgn(jb)};
}

// The integrands at θ for sinkage z and slip s: {vertical, longitudinal} per unit angle.
inline void integrands(const Soil& soil, const Wheel& w, double z, double s, double theta,
                       const Shares& shares, double& vertical, double& longitudinal) {
  const double theta1 = std::acos(1.0 - z / w.r);
  double ratio = soil.c1 + soil.c2 * s;
  ratio = ratio < 0.0 ? 0.0 : (ratio > 1.0 ? 1.0 : ratio);
  const double theta_m = ratio * theta1;
  const double n = soil.n0 + soil.n1 * std::fabs(s);
  const double star = theta >= theta_m ? theta : theta1 - theta * (theta1 - theta_m) / theta_m;
  const double base = std::cos(star) - std::cos(theta1);
  const double sigma = (soil.kc / w.b + soil.kphi) * std::pow(w.r * (base > 0.0 ? base : 0.0), n);
  double tau = 0.0;
  if (!w.bladed) {
    tau = (soil.c + sigma * std::tan(soil.phi)) * shares.across;
  } else {
    const double across = (soil.c + sigma * std::tan(soil.phi)) * shares.across;
    const double along = sigma * std::tan(soil.delta) * shares.along;
    tau = across * std::cos(w.inclination) + along * w.handedness * std::sin(w.inclination);
  }
  vertical = w.b * (sigma * w.r * std::cos(theta) + tau * w.rs * std::sin(theta));
  longitudinal = w.b * (tau * w.rs * std::cos(theta) - sigma * w.r * std::sin(theta));
}

inline Result integrate(const Soil& soil, const Wheel& w, double z, double s) {
  Result result{0.0, 0.0, z};
  const double theta1 = std::acos(1.0 - z / w.r);
  double ratio = soil.c1 + soil.c2 * s;
  ratio = ratio < 0.0 ? 0.0 : (ratio > 1.0 ? 1.0 : ratio);
  const double bounds[3] = {0.0, ratio * theta1, theta1};
  constexpr int kIntervals = 2000;  // even, per side
  // The elastoplastic shares along the arc from the entry down, at every node of both sides
  // (side 1, θm…θ1, then side 0, 0…θm), each node's reached from the one above it in θ.
  Shares path{0.0, 0.0};
  double last_j = 0.0;
  const auto follow = [&](double theta) {
    const double j = displacement(w, z, s, theta);
    const double dj = j - last_j;
    last_j = j;
    const double dn = w.bladed ? dj * std::cos(w.inclination) : dj;
    const double db = w.bladed ? dj * w.handedness * std::sin(w.inclination) : 0.0;
    path = {share_step(path.across, dn, soil.K, soil.unloading_ratio),
            share_step(path.along, db, soil.K, soil.unloading_ratio)};
    return path;
  };
  constexpr int kSubsteps = 8;  // per Simpson interval, for the path's integration
  for (int side = 1; side >= 0; --side) {
    const double a = bounds[side], h = (bounds[side + 1] - a) / kIntervals;
    if (h <= 0.0) continue;
    for (int i = kIntervals; i >= 0; --i) {
      const double theta = a + i * h;
      Shares shares{};
      if (soil.unloading_ratio > 0.0) {
        if (i < kIntervals) {
          for (int k = kSubsteps - 1; k >= 1; --k) follow(theta + h * k / kSubsteps);
        }
        shares = follow(theta);
      } else {
        shares = classic_shares(soil, w, z, s, theta);
      }
      const double weight = (i == 0 || i == kIntervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
      double vertical = 0.0, longitudinal = 0.0;
      integrands(soil, w, z, s, theta, shares, vertical, longitudinal);
      result.weight_n += weight * h / 3.0 * vertical;
      result.drawbar_pull_n += weight * h / 3.0 * longitudinal;
    }
  }
  return result;
}

// The wheel at load W and slip s: the sinkage by bisection on the reference's own W(z).
inline Result at_load(const Soil& soil, const Wheel& w, double load_n, double s) {
  double low = 1e-9, high = w.r;
  for (int i = 0; i < 80; ++i) {
    const double mid = 0.5 * (low + high);
    (integrate(soil, w, mid, s).weight_n < load_n ? low : high) = mid;
  }
  return integrate(soil, w, 0.5 * (low + high), s);
}

}  // namespace marsokhod::sim::soil::reference
