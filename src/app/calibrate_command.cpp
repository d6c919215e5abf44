#include "app/calibrate_command.hpp"

#include <iomanip>
#include <memory>
#include <optional>
#include <string>
#include <istream>
#include <ostream>

#include "bus/transport.hpp"
#include "calibration/calibration_file.hpp"
#include "calibration/procedures.hpp"
#include "sim/rover/simulated_rover.hpp"

namespace marsokhod::app {
namespace {

constexpr int kRefused = 1;
constexpr int kUsageError = 2;

void list_procedures(std::ostream& out) {
  for (const calibration::ProcedureInfo& p : calibration::procedures()) {
    out << std::left << std::setw(15) << p.name << std::setw(16) << (p.reference + " ")
        << p.summary
        << (p.needs_bench ? "" : " (no rover needed)") << "\n";
  }
}

std::string names() {
  std::string all;
  for (const calibration::ProcedureInfo& p : calibration::procedures()) {
    all += (all.empty() ? "" : ", ") + p.name;
  }
  return all;
}

void print_result(const calibration::ProcedureResult& r, std::ostream& out) {
  out << r.reference << " (" << r.procedure << "):\n";
  std::ostringstream values;
  values << r.values;
  std::istringstream lines(values.str());
  for (std::string line; std::getline(lines, line);) out << "  " << line << "\n";
  for (const auto& [name, value] : r.quality) out << "  " << name << " = " << value << "\n";
  for (const std::string& note : r.notes) out << "  note: " << note << "\n";
}

}  // namespace

namespace {

// What is wrong with the arguments for this procedure (one line), or nothing.
std::optional<std::string> argument_problem(const CalibrateArgs& args,
                                            const calibration::ProcedureInfo& info) {
  if (info.needs_bench) {
    if (args.sim == !args.can.empty()) {
      return "say where the rover is: --sim (the simulated rover) or --can URL";
    }
    if (!args.from.empty()) return "--from is for voltage-drop only";
    if (args.ground && !args.sim) return "--ground is for the simulated rover (--sim) only";
    if (args.ground && !sim::material_named(*args.ground)) {
      return "--ground " + *args.ground + " is unknown; use hard, sand, grass or lunar-soil" +
             sim::retired_material_note(*args.ground);
    }
  } else if (args.from.empty()) {
    return "--from DIR is required (a scenario's --out folder with telemetry.csv)";
  }
  return std::nullopt;
}

std::unique_ptr<calibration::Bench> open_bench(const CalibrateArgs& args,
                                               const calibration::ProcedureInfo& info,
                                               const config::LoadedConfig& config,
                                               std::istream& in, std::ostream& out) {
  if (args.sim) {
    sim::SimOptions sim_options = calibration::sim_bench_options(args.seed);
    if (info.on_battery) sim_options.supply = sim::SupplyKind::kBattery;
    if (args.ground) sim_options.terrain.ground = *sim::material_named(*args.ground);
    return std::make_unique<calibration::SimBench>(config.params, sim_options, config.nominal);
  }
  return std::make_unique<calibration::BusBench>(config.params, bus::open_transport(args.can), in,
                                                 out);
}

// The plots (--plot) and the calibration file. 0, kUsageError or kRefused.
int write_outputs(const CalibrateArgs& args, const calibration::ProcedureInfo& info,
                  const calibration::ProcedureResult& result, const config::LoadedConfig& config,
                  const std::string& source, std::ostream& out, std::ostream& err) {
  if (!args.plot.empty()) {
    try {
      if (const auto note = calibration::write_recordings(result.recordings, args.plot)) {
        out << "  " << *note << "\n";
      } else {
        out << "  measured data and plots in " << args.plot << "\n";
      }
    } catch (const std::exception& e) {
      err << "marsokhod calibrate " << info.name << ": " << e.what() << "\n";
      return kUsageError;
    }
  }
  try {
    calibration::write_calibration(args.out, result, config.config_file, source, args.force);
  } catch (const calibration::CalibrationRefused& e) {
    err << "marsokhod " << e.what() << "\n";
    return kRefused;
  }
  out << "wrote " << args.out << " (load it with --calibration " << args.out << ")\n";
  return 0;
}

}  // namespace

int run_calibrate_command(const CalibrateArgs& args, const config::LoadedConfig& config,
                          std::istream& in, std::ostream& out, std::ostream& err) {
  if (args.list) {
    list_procedures(out);
    return 0;
  }
  const calibration::ProcedureInfo* info = calibration::find_procedure(args.procedure);
  if (info == nullptr) {
    err << "marsokhod calibrate: no procedure '" << args.procedure << "'; one of " << names()
        << "\n";
    return kUsageError;
  }
  if (const auto problem = argument_problem(args, *info)) {
    err << "marsokhod calibrate " << info->name << ": " << *problem << "\n";
    return kUsageError;
  }
  calibration::ProcedureOptions options;
  options.duration_s = args.duration_s;
  options.icr = args.icr;
  if (!args.from.empty()) options.from = args.from;
  std::unique_ptr<calibration::Bench> bench;
  std::string source = args.from.empty() ? "" : "recording " + args.from;
  calibration::ProcedureResult result;
  try {
    if (info->needs_bench) {
      bench = open_bench(args, *info, config, in, out);
      source = bench->source();
      out << "marsokhod calibrate " << info->name << ": " << info->reference << " on " << source
          << "; " << config::describe_calibration(config.calibration) << "\n";
    }
    result = calibration::run_procedure(bench.get(), *info, config.params, options);
    if (bench) bench->stop();
  } catch (const std::exception& e) {
    err << "marsokhod calibrate " << info->name << ": " << e.what() << "\n";
    return kUsageError;
  }
  print_result(result, out);
  if (bench) {
    out << "  measured for " << std::fixed << std::setprecision(1) << bench->time_s()
        << " s of bench time" << std::defaultfloat << "\n";
  }
  return write_outputs(args, *info, result, config, source, out, err);
}

}  // namespace marsokhod::app
