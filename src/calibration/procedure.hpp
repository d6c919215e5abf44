// What a calibration procedure hands back: the values it fitted, in the configuration's own
// sections and keys (so the calibration file reads like config/marsokhod.toml), how good the fit
// was, the reasons to refuse it, and the data it measured (for --plot).
#pragma once

#include <toml++/toml.h>

#include <filesystem>
#include <cstddef>
#include <functional>
#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/params.hpp"

namespace marsokhod::calibration {

class Bench;

// A measured series for plots and the report: named columns of equal length.
struct Recording {
  std::string name;                  // file stem: "voltage" → voltage.csv, voltage.png
  std::string title;                 // the plot's title, citing the thesis' figure
  std::vector<std::string> columns;  // names with units: "vcc_counts", "supply_v"
  std::vector<std::vector<double>> rows;
  // gnuplot commands drawing the plot from "<name>.csv" (columns by name); empty: no plot.
  std::string gnuplot;
};

struct ProcedureResult {
  std::string procedure;   // "voltage"
  std::string reference;   // "Procedure 3.5"
  // The fitted values: {"sensors": {"supply_v_per_count": …, "supply_offset_v": …}}; arrays of
  // tables for "motor_curve" and "response" as in config/marsokhod.toml.
  toml::table values;
  // How good the fit is, named with units ("rms_residual_v", "samples"); written with the values.
  std::map<std::string, double> quality;
  // Why the fit must not be written; empty when it is good.
  std::vector<std::string> problems;
  std::vector<Recording> recordings;
  std::vector<std::string> notes;  // said to the user, not judged

  bool accepted() const { return problems.empty(); }
};

// Options every procedure understands; each uses what applies to it.
struct ProcedureOptions {
  std::optional<double> duration_s;        // motor-scale (default 120 s), response (default 120 s)
  std::optional<int> icr;                  // motor-curve, load (default: the configured icr)
  std::optional<std::filesystem::path> from;  // voltage-drop: a scenario's --out folder
};

// Writes every recording as <dir>/<name>.csv and, when gnuplot is installed, <name>.png. Returns
// a note when gnuplot is missing (the CSVs are still written); throws std::runtime_error when
// the folder cannot be written.
std::optional<std::string> write_recordings(const std::vector<Recording>& recordings,
                                            const std::filesystem::path& dir);

// --duration, or `default_s` when not given. Throws std::invalid_argument naming the procedure
// when it is not positive.
double duration_of(const ProcedureOptions& options, double default_s, std::string_view procedure);

// The wheels the stand procedures measure: all six (the joints cannot turn freely on the stand).
std::vector<std::size_t> all_wheels();

// `value` in fixed notation with `digits` digits after the point: fixed(24.0, 1) = "24.0".
std::string fixed(double value, int digits = 3);

}  // namespace marsokhod::calibration
