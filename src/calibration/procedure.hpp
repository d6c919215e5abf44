// The skeleton every calibration procedure runs in, and what a procedure hands back: the values
// it fitted, in the configuration's own sections and keys (so the calibration file reads like
// config/marsokhod.toml), how good the fit was, the reasons to refuse it, and the data it
// measured (for --plot).
//
// run_procedure(bench, spec) does what all procedures share: it resolves --duration and --icr,
// arranges the rover and starts the bench, runs the procedure's command, stops the motors, puts
// the rover back, fits, and names the result. A procedure (a Procedure) gives only its command
// (where the rover stands, what each cycle asks of the motors, what it keeps) and its fit; its
// name and thesis reference are in the registry (registry.cpp).
#pragma once

#include <toml++/toml.h>

#include <filesystem>
#include <cstddef>
#include <functional>
#include <iosfwd>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "calibration/bench.hpp"
#include "core/params.hpp"

namespace marsokhod::calibration {

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

// The settings of one run of a procedure.
struct Run {
  const Params& params;             // the bench's (the driver side's) configuration
  const ProcedureOptions& options;
  double duration_s = 0.0;          // --duration, or the procedure's default
  int icr = 0;                      // --icr, or the configured
  double period_s() const { return params.cycle.period_s; }
};

// One cycle of a run: the sample, and the supply voltage the driver would have used for the duty
// it sent (the latest µ8 measured before the cycle; Ū until it answered).
struct RunCycle {
  std::size_t k = 0;
  const BenchSample& sample;
  double supply_sent_v = 0.0;
};

// One procedure: its command and its fit. run_procedure makes a fresh one for every run, so it
// keeps what it measures in its members.
class Procedure {
 public:
  Procedure() = default;
  virtual ~Procedure() = default;
  Procedure(const Procedure&) = delete;
  Procedure& operator=(const Procedure&) = delete;

  // --duration when not given [s]; 0: the procedure does not use it.
  virtual double default_duration_s() const { return 0.0; }
  // Checks what the run needs of the configuration before the rover is touched (throws).
  virtual void prepare(const Run& /*run*/) {}
  // Where the rover stands: arranged, the bench then (re)started at the run's icr, and the
  // motors stopped after the command. nullopt: the command arranges the rover itself, place by
  // place (the bench started at the configured icr unless it runs already).
  virtual std::optional<BenchSetup> setup(const Run& /*run*/) const { return std::nullopt; }
  // The command. By default cycles() cycles of wanted(), each handed to record().
  virtual void command(Bench& bench, const Run& run);
  // Where the rover goes after the command; nullopt: it stays.
  virtual std::optional<BenchSetup> teardown(const Run& /*run*/) const { return std::nullopt; }
  // The fitted values, their quality, the problems, the notes and the recordings, from what the
  // command measured (the skeleton adds the procedure's name and reference).
  virtual ProcedureResult fit(const Run& run) const = 0;

 protected:
  // The default command's cycles; wanted() is given the latest measured supply voltage.
  virtual std::size_t cycles(const Run& /*run*/) const { return 0; }
  virtual MotorVector wanted(std::size_t /*k*/, double /*supply_v*/, const Run& /*run*/) const {
    return {};
  }
  virtual void record(const RunCycle& /*cycle*/, const Run& /*run*/) {}
};

// The stand with the wheels free at Ū (stand_at_nominal_supply) for a run of --duration: the
// instruction goes on with `then`, " for <duration> s.".
BenchSetup stand_for_run(const Run& run, std::string_view then);

// A procedure as the registry lists it.
struct ProcedureInfo {
  std::string name;       // "motor-curve"
  std::string reference;  // "Procedure 4.4"
  std::string summary;    // one line for --help
  bool needs_bench = true;  // false: voltage-drop works on a recording
  // The simulated bench runs on the battery rather than the laboratory tether (whose 6 A limit
  // a spinning rover exceeds).
  bool on_battery = false;
  std::function<std::unique_ptr<Procedure>()> make;
};

// Runs `spec` on `bench` (nullptr when spec.needs_bench is false; then `params` are used, else
// the bench's). Throws std::invalid_argument for a --duration that is not positive, and what
// the procedure or the bench throws.
ProcedureResult run_procedure(Bench* bench, const ProcedureInfo& spec, const Params& params,
                              const ProcedureOptions& options);

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

// `value` rounded to a multiple of 1/per_unit, for the calibration file: rounded(x, 1e4).
double rounded(double value, double per_unit);

// The first lines of a plot whose columns the CSV's header names.
inline constexpr const char* kPlotByColumnHeads =
    "set termoption noenhanced\nset key autotitle columnhead\n";

}  // namespace marsokhod::calibration
