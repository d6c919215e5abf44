// The calibration procedures of the thesis and the registry the `marsokhod calibrate PROCEDURE`
// command picks from. Each procedure is a Procedure (procedure.hpp) — its command on the Bench
// (the simulated rover or a real bus) and its fit — that run_procedure runs; its result's
// `problems` say why a poor fit must not be written. The fits are separate functions of the
// measured data (accelerometer.hpp, voltage.hpp, …) so that tests can feed them noisy or short
// data.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "calibration/bench.hpp"
#include "calibration/procedure.hpp"

namespace marsokhod::calibration {

// The procedures, each a fresh one for one run (registered by name in registry.cpp).
std::unique_ptr<Procedure> accelerometer_procedure();  // the ±g table, axis by axis, on the stand
std::unique_ptr<Procedure> tilt_procedure();           // θf, θr at the stops and level
std::unique_ptr<Procedure> voltage_procedure();        // U = gain·vcc + offset, 27 … 20 V
std::unique_ptr<Procedure> joints_procedure();         // joint initialisation and backlash
std::unique_ptr<Procedure> motor_curve_procedure();    // W_icr(d) by a slow pwm sweep
std::unique_ptr<Procedure> motor_scale_procedure();    // ζ_i at d = 0.7 with the warm-up
std::unique_ptr<Procedure> response_procedure();       // δ of (4.4) from a chirp
std::unique_ptr<Procedure> load_procedure();           // B⁺, B⁻ from a weight on a wheel
std::unique_ptr<Procedure> load_gain_procedure();      // B±_icr(d) at three supply voltages
std::unique_ptr<Procedure> spin_procedure();           // F̂(c) and the line F(c)
std::unique_ptr<Procedure> voltage_drop_procedure();   // ξ, Ξ of (4.5) from a recording

// In the order of the thesis.
const std::vector<ProcedureInfo>& procedures();
// nullptr when there is no procedure of that name.
const ProcedureInfo* find_procedure(std::string_view name);

// The procedure of that name on `bench` (std::invalid_argument for an unknown name).
ProcedureResult run_procedure(Bench& bench, std::string_view name,
                              const ProcedureOptions& options = {});

}  // namespace marsokhod::calibration
