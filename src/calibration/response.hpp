// Procedure 4.8: the coefficients δ^j of (4.4), ν^k = Σ_j δ^j ŵ^(k−j), for the bench's (h, con),
// by least squares from a chirp: the wheels on the stand are given a no-load velocity ŵ that
// oscillates with rising frequency (Figure 4.4), and δ solves
//   w^k = Σ_(j=1..N) δ^j ŵ^(k−j)
// over every measured wheel and cycle. δ⁰ = 0: the command sent in cycle k cannot affect the
// velocity µi samples when that very request arrives.
//
// Indexing: the thesis'. A Bench cycle m sends d_m and returns v_m, µi's answer to that request,
// sampled when it arrived — the thesis' w^m:
//   v_m = Σ_(j=1..N) δ^j ŵ_(m−j)
// so the table compares with the thesis' and with the configuration's. (The driver receives v_m
// one cycle later and applies the table one cycle late: driver/motion_controller.cpp.)
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "calibration/fit.hpp"

namespace marsokhod::calibration {

// The command of Figure 4.4: ŵ(t) = c + A(f)·sin φ(t), the frequency f rising linearly from
// start_hz to end_hz over duration_s. The lags of (4.4) are h apart, so telling them apart takes
// frequencies up to near the Nyquist frequency 1/(2h); linearly, so that those get most of the
// time. The amplitude is limited so that ŵ changes by at most max_step_radps per cycle
// (2A·sin(πfh) ≤ max_step: the duty's slew limit of chapter 3.2 must not distort the chirp).
struct Chirp {
  double center_radps = 1.2;
  double amplitude_radps = 0.8;
  double start_hz = 0.1;
  double end_hz = 28.0;
  double duration_s = 120.0;
  double period_s = 0.0156;
  double max_step_radps = 0.12;
  double frequency_hz(double t_s) const;
  double operator()(double t_s) const;
};

// One wheel's run, per bench cycle m: ŵ_m = ζ·W(d_m)·U_m/Ū of the duty sent, and v_m.
struct ResponseSeries {
  std::vector<double> commanded_radps;  // ŵ_m
  std::vector<double> measured_radps;   // v_m, sampled when request m arrived (the thesis' w^m)
};

struct ResponseFitSettings {
  std::size_t order = 7;        // N: δ¹ … δ^N are fitted (the stand's chain lasts ≈ 6 cycles)
  double period_s = 0.0156;     // h
  double min_duration_s = 30.0;
  // Refusals: a command that does not excite every lag (the smallest over the largest eigenvalue
  // of the covariance of N consecutive ŵ: a single frequency has two non-zero ones), a δ^j the
  // data does not pin down (standard error, corrected for the residuals' correlation), and a
  // poor model (rms residual).
  double min_excitation = 1e-3;
  double max_standard_error = 0.02;
  double max_residual_radps = 0.05;
};

struct ResponseFit {
  std::vector<double> delta;           // δ⁰ = 0, δ¹ … δ^N
  std::vector<double> standard_error;  // of each δ^j (δ⁰: 0)
  Residuals residuals;                 // of w − ν over the fitted cycles [rad/s]
  double sum = 0.0;                    // Σ δ^j (1 when ŵ matches the wheels' speeds)
  double excitation = 0.0;             // see ResponseFitSettings::min_excitation
  double duration_s = 0.0;             // of each wheel's run
  std::size_t rows = 0;
  std::vector<std::string> problems;
};

// Never throws for bad data (problems say why); std::invalid_argument for series of unequal
// length or an order of 0.
ResponseFit fit_response(const std::vector<ResponseSeries>& wheels,
                         const ResponseFitSettings& settings);

// ν aligned with v: ν_m = Σ_j δ^j ŵ_(m−j), with ŵ before the start taken as the first command.
std::vector<double> predict_response(const std::vector<double>& delta,
                                     const std::vector<double>& commanded_radps);

}  // namespace marsokhod::calibration
