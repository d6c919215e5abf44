// The calibration procedures of the thesis, one function each, and the table the
// `marsokhod calibrate PROCEDURE` command picks from. Each measures on a Bench (the simulated
// rover or a real bus), fits, and returns a ProcedureResult whose `problems` say why a poor fit
// must not be written. The fits are separate functions of the measured data so that tests can
// feed them noisy or short data.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "calibration/bench.hpp"
#include "calibration/procedure.hpp"

namespace marsokhod::calibration {

// Procedure 3.3: the ±g table of the accelerometer, axis by axis, on the stand.
ProcedureResult calibrate_accelerometer(Bench& bench, const ProcedureOptions& options);
// Procedure 3.5: U = gain·vcc + offset from readings at supply voltages 27 … 20 V.
ProcedureResult calibrate_voltage(Bench& bench, const ProcedureOptions& options);
// Procedure 4.3 (with 4.1): joint initialisation, and the joints' backlash.
ProcedureResult calibrate_joints(Bench& bench, const ProcedureOptions& options);
// Procedure 4.4: W_icr(d) by a slow pwm sweep on the stand, normalised by Ū/U.
ProcedureResult calibrate_motor_curve(Bench& bench, const ProcedureOptions& options);
// Procedure 4.5: ζ_i of each wheel at d = 0.7, with the warm-up of Figure 4.3.
ProcedureResult calibrate_motor_scale(Bench& bench, const ProcedureOptions& options);
// Procedure 4.8: δ of (4.4) by least squares from a chirp, for the bench's (h, con).
ProcedureResult calibrate_response(Bench& bench, const ProcedureOptions& options);
// Procedure 4.13: B⁺ and B⁻ of (4.6)/(4.7) from a weight strapped to the front-left wheel.
ProcedureResult calibrate_load(Bench& bench, const ProcedureOptions& options);
// Procedure 5.1: F̂(c) at several axle distances and the line F(c).
ProcedureResult calibrate_spin(Bench& bench, const ProcedureOptions& options);
// Chapter 4.2, (4.5): ξ and Ξ from a recorded drive (options.from: a scenario's --out folder
// with telemetry.csv). Needs no bench.
ProcedureResult calibrate_voltage_drop(const Params& params, const ProcedureOptions& options);

struct ProcedureInfo {
  std::string name;       // "motor-curve"
  std::string reference;  // "Procedure 4.4"
  std::string summary;    // one line for --help
  bool needs_bench = true;  // false: voltage-drop works on a recording
  // The simulated bench runs on the battery rather than the laboratory tether (whose 6 A limit
  // a spinning rover exceeds).
  bool on_battery = false;
  // bench is nullptr when needs_bench is false.
  std::function<ProcedureResult(Bench* bench, const Params& params,
                                const ProcedureOptions& options)>
      run;
};

// In the order of the thesis.
const std::vector<ProcedureInfo>& procedures();
// nullptr when there is no procedure of that name.
const ProcedureInfo* find_procedure(const std::string& name);

}  // namespace marsokhod::calibration
