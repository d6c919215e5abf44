// Procedure 5.1: the exterior-to-center wheel speed ratio F̂(c) of the most efficient spin at
// several equidistant axle distances c = c_f = c_r, and the line F(c) = slope·c + offset.
//
// At each c the rover rests on flat ground of one texture and gets the duty cycles
//   d(τ) = 0.8·[ +½(1+τ)  +(1−τ)  +½(1+τ) ]   (left column: BL, CL, FL)
//              [ −½(1+τ)  −(1−τ)  −½(1+τ) ]   (right: BR, CR, FR)
// with τ ramping slowly from 0 to 1 (Σ|d_i| = 3.2 throughout, "an invariant level of energy").
// At the instant of the largest turning rate |ω3| (the gyro, (3.4))
//   F̂(c) = ¼(w0 − w1 + w4 − w5) / ½(w2 − w3)
// from the measured wheel speeds. The joints are set between the spins on the stand (wheels
// free) by a small closed loop on the shafts through the configured backlash (4.1).
#pragma once

#include <functional>
#include <vector>

#include "calibration/bench.hpp"
#include "calibration/procedure.hpp"
#include "core/params.hpp"

namespace marsokhod::calibration {

// The thesis' line, F(c) := 5.3c + 0.04 (chapter 5.1, fitted to Marsokhod's F̂ of Figure 5.4; the
// configuration's [spin] default). Procedure 5.1 reports what it measures beside it.
inline constexpr double kThesisSpinSlopePerM = 5.3;
inline constexpr double kThesisSpinOffset = 0.04;

// d(τ) of Procedure 5.1 (joints 0).
MotorVector spin_duty(double tau);

// The joint angle γ giving the clearance c (the chapter 5 table's c(γ) inverted):
// γ = acos((a² + b² − c²)/(2ab)). Throws std::invalid_argument outside a − b < c < a + b.
double bending_for_clearance(double clearance_m, const GeometryParams& geometry);

// One cycle of a sweep.
struct SpinSample {
  double time_s = 0.0;  // since the sweep started
  double tau = 0.0;
  double turn_rate_radps = 0.0;  // ω3 by (3.4) with the null rate measured at rest before
  MotorVector velocity_radps{};  // w̄_i
};

// One sweep at one axle distance.
struct SpinSweep {
  double clearance_m = 0.0;  // c from the joints' positions reached, (c_f + c_r)/2
  std::vector<SpinSample> samples;
  // The gyro's standard deviation over the rest in which its null rate was taken, as a rate: a
  // rover still moving then (settling after it was set down) offsets the whole sweep's ω3.
  double null_spread_radps = 0.0;
};

// What one sweep gives.
struct SpinPoint {
  double clearance_m = 0.0;
  double ratio = 0.0;            // F̂(c)
  double tau = 0.0;              // where the turning rate peaked
  double time_s = 0.0;
  double turn_rate_radps = 0.0;  // |ω3| there (averaged like the wheel speeds)
  bool measured = false;         // the sweep had the cycles to find a peak in
};

struct SpinLimits {
  std::size_t min_clearances = 3;
  std::size_t min_samples = 200;       // per sweep
  double averaging_s = 0.5;            // centered moving average of ω3 and w̄ before the peak
  double edge_tau = 0.05;              // a peak this close to τ = 0 or 1 was not bracketed
  double min_turn_rate_radps = 0.05;   // the rover must turn
  double max_null_spread_radps = 0.05; // and stand still while the gyro's null is taken
  double max_rms_residual = 0.15;      // of F̂ about the line
};

// F̂ at the peak of one sweep (the sweep's problems are added to `problems`).
SpinPoint spin_point(const SpinSweep& sweep, const SpinLimits& limits,
                     std::vector<std::string>& problems);

// F(c) from the sweeps; refuses too few clearances, a sweep whose rest was not still, unbracketed
// peaks, F̂ ≤ 1, a line falling with c, or a poor line. Accepted or not, its notes give each
// sweep's F̂, peak turning rate and τ beside the thesis' F(c), and the line through the F̂ (from
// two axle distances on) beside the thesis' line.
ProcedureResult fit_spin(const std::vector<SpinSweep>& sweeps, const SpinLimits& limits = {});

// One sweep on the ground as it stands: rests 1 s for the gyro's null rate, then ramps τ over
// ramp_s. `observe` (if given) sees every bench sample (tests compare with the simulator).
SpinSweep run_spin_sweep(Bench& bench, double clearance_m, double ramp_s,
                         const std::function<void(const BenchSample&)>& observe = {});

// The axle distances the procedure visits [m], within the joint bounds (5.3).
const std::vector<double>& spin_clearances_m();

}  // namespace marsokhod::calibration
