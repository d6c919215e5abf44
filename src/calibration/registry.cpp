#include "calibration/procedures.hpp"

namespace marsokhod::calibration {
namespace {

ProcedureInfo with_bench(std::string name, std::string reference, std::string summary,
                         ProcedureResult (*run)(Bench&, const ProcedureOptions&)) {
  return {std::move(name), std::move(reference), std::move(summary), true, false,
          [run](Bench* bench, const Params&, const ProcedureOptions& options) {
            return run(*bench, options);
          }};
}

}  // namespace

const std::vector<ProcedureInfo>& procedures() {
  static const std::vector<ProcedureInfo> table = [] {
    std::vector<ProcedureInfo> t;
    t.push_back(with_bench("accelerometer", "Procedure 3.3",
                           "the accelerometer's ±g table, axis by axis", calibrate_accelerometer));
    t.push_back(with_bench("voltage", "Procedure 3.5",
                           "U = gain·vcc + offset at supply voltages 27 … 20 V", calibrate_voltage));
    t.push_back(with_bench("joints", "Procedure 4.3",
                           "joint initialisation and the joints' backlash", calibrate_joints));
    t.push_back(with_bench("motor-curve", "Procedure 4.4",
                           "W_icr(d) by a slow pwm sweep, normalised by U-bar/U",
                           calibrate_motor_curve));
    t.push_back(with_bench("motor-scale", "Procedure 4.5", "ζ of each wheel at d = 0.7",
                           calibrate_motor_scale));
    t.push_back(with_bench("response", "Procedure 4.8",
                           "δ of (4.4) by least squares from a chirp", calibrate_response));
    t.push_back(with_bench("load", "Procedure 4.13",
                           "B+ and B- of (4.6) from a weight strapped to a wheel", calibrate_load));
    t.push_back(with_bench("spin", "Procedure 5.1",
                           "F^(c) at several axle distances and the line F(c)", calibrate_spin));
    t.back().on_battery = true;
    t.push_back({"voltage-drop", "(4.5)",
                 "xi and Xi of (4.5) from a recorded drive (--from DIR)", false, false,
                 [](Bench*, const Params& params, const ProcedureOptions& options) {
                   return calibrate_voltage_drop(params, options);
                 }});
    return t;
  }();
  return table;
}

const ProcedureInfo* find_procedure(const std::string& name) {
  for (const ProcedureInfo& info : procedures()) {
    if (info.name == name) return &info;
  }
  return nullptr;
}

}  // namespace marsokhod::calibration
