// The procedures by name, with their thesis references (procedures.hpp).
#include "calibration/procedures.hpp"

#include <stdexcept>

namespace marsokhod::calibration {

const std::vector<ProcedureInfo>& procedures() {
  static const std::vector<ProcedureInfo> table{
      {"accelerometer", "Procedure 3.3", "the accelerometer's ±g table, axis by axis", true, false,
       accelerometer_procedure},
      {"tilt", "Procedure 3.4",
       "θf, θr = gain·tlt + offset at the ±30° stops and level, play taken out", true,
       false, tilt_procedure},
      {"voltage", "Procedure 3.5", "U = gain·vcc + offset at supply voltages 27 … 20 V", true,
       false, voltage_procedure},
      {"joints", "Procedure 4.3, Procedure 4.1", "joint initialisation and the joints' backlash",
       true, false, joints_procedure},
      {"motor-curve", "Procedure 4.4", "W_icr(d) by a slow pwm sweep, normalised by U-bar/U",
       true, false, motor_curve_procedure},
      {"motor-scale", "Procedure 4.5", "ζ of each wheel at d = 0.7", true, false,
       motor_scale_procedure},
      {"response", "Procedure 4.8", "δ of (4.4) by least squares from a chirp", true, false,
       response_procedure},
      {"load", "Procedure 4.13", "B+ and B- of (4.6) from a weight strapped to a wheel", true,
       false, load_procedure},
      {"load-gain", "Procedure 4.14, Procedure 4.13",
       "B+_icr(d), B-_icr(d) of (4.6) at five duties and three supply voltages", true, false,
       load_gain_procedure},
      {"spin", "Procedure 5.1", "F^(c) at several axle distances and the line F(c)", true, true,
       spin_procedure},
      {"voltage-drop", "(4.5)", "xi and Xi of (4.5) from a recorded drive (--from DIR)", false,
       false, voltage_drop_procedure},
  };
  return table;
}

const ProcedureInfo* find_procedure(std::string_view name) {
  for (const ProcedureInfo& info : procedures()) {
    if (info.name == name) return &info;
  }
  return nullptr;
}

ProcedureResult run_procedure(Bench& bench, std::string_view name,
                              const ProcedureOptions& options) {
  const ProcedureInfo* info = find_procedure(name);
  if (info == nullptr) {
    throw std::invalid_argument("no calibration procedure '" + std::string(name) + "'");
  }
  return run_procedure(&bench, *info, bench.params(), options);
}

}  // namespace marsokhod::calibration
