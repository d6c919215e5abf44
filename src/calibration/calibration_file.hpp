// Writing the calibration file: the fitted values in config/marsokhod.toml's own sections and
// keys, which the driver loads on top of the configuration (config/calibration.hpp), and per
// procedure a [calibration.<procedure>] table with where it was measured and how good the fit
// was.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "calibration/procedure.hpp"

namespace marsokhod::calibration {

// Refused: a poor fit, an existing file without --force, values the configuration would not
// accept. The message says why.
class CalibrationRefused : public std::runtime_error {
 public:
  using runtime_error::runtime_error;
};

// Writes `result` to `file`. Refuses when the result has problems, when `file` exists and
// `force` is false, or when the values merged into `config_file` would not load. With `force`,
// an existing calibration file keeps what other procedures wrote and only this procedure's
// values and report are replaced. `source` names where it was measured.
void write_calibration(const std::filesystem::path& file, const ProcedureResult& result,
                       const std::filesystem::path& config_file, const std::string& source,
                       bool force);

}  // namespace marsokhod::calibration
