// The configuration a command runs with: config/marsokhod.toml, and the calibration file on top
// of it for the driver (--calibration FILE or $MARSOKHOD_CALIBRATION).
#pragma once

#include <filesystem>
#include <string>

#include "config/configuration.hpp"
#include "core/params.hpp"

namespace marsokhod::config {

struct LoadedConfig {
  Params nominal;  // the configuration alone: what the simulated rover is built from
  Params params;   // the driver's: the configuration with the calibration on top
  config::ConsoleParams console;          // [console]
  config::CalibrationSource calibration;  // where `params` differ from `nominal`
  std::filesystem::path config_file;
  std::filesystem::path calibration_file;  // empty: none
};

// "calibration: cal.toml (voltage, motor-scale)" or "calibration: none (nominal configuration)".
inline std::string describe_calibration(const config::CalibrationSource& calibration) {
  if (calibration.file.empty()) return "calibration: none (nominal configuration)";
  std::string procedures;
  for (const std::string& p : calibration.procedures) {
    procedures += (procedures.empty() ? "" : ", ") + p;
  }
  return "calibration: " + calibration.file + " (" +
         (procedures.empty() ? "no procedures" : procedures) + ")";
}

}  // namespace marsokhod::config
