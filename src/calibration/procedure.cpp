// The skeleton of every procedure, and what the procedures share: --duration, the wheels they
// drive, numbers in messages and in the calibration file (procedure.hpp).
#include "calibration/procedure.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace marsokhod::calibration {

void Procedure::command(Bench& bench, const Run& run) {
  double supply_v = run.params.motors.nominal_supply_v;
  const std::size_t n = cycles(run);
  for (std::size_t k = 0; k < n; ++k) {
    const double supply_sent_v = supply_v;
    const BenchSample& s = bench.cycle(wanted(k, supply_sent_v, run));
    if (s.sensors.supply_v > 0.0) supply_v = s.sensors.supply_v;
    record({k, s, supply_sent_v}, run);
  }
}

ProcedureResult run_procedure(Bench* bench, const ProcedureInfo& spec, const Params& params,
                              const ProcedureOptions& options) {
  const std::unique_ptr<Procedure> procedure = spec.make();
  const Params& used = bench != nullptr ? bench->params() : params;
  const double default_s = procedure->default_duration_s();
  const Run run{used, options, default_s > 0.0 ? duration_of(options, default_s, spec.name) : 0.0,
                options.icr.value_or(used.cycle.icr)};
  procedure->prepare(run);
  if (bench != nullptr) {
    const std::optional<BenchSetup> setup = procedure->setup(run);
    if (setup) {
      bench->arrange(*setup);
      bench->start(run.icr, used.cycle.con);
    } else if (!bench->started()) {
      bench->start(used.cycle.icr, used.cycle.con);
    }
    procedure->command(*bench, run);
    if (setup) bench->stop();
    if (const std::optional<BenchSetup> after = procedure->teardown(run)) bench->arrange(*after);
  }
  ProcedureResult result = procedure->fit(run);
  result.procedure = spec.name;
  result.reference = spec.reference;
  return result;
}

BenchSetup stand_for_run(const Run& run, std::string_view then) {
  return stand_at_nominal_supply(run.params,
                                 std::string(then) + " for " + fixed(run.duration_s, 0) + " s.");
}

double duration_of(const ProcedureOptions& options, double default_s, std::string_view procedure) {
  const double duration_s = options.duration_s.value_or(default_s);
  if (!(duration_s > 0.0)) {
    throw std::invalid_argument(std::string(procedure) + ": --duration must be > 0 s");
  }
  return duration_s;
}

std::vector<std::size_t> all_wheels() {
  std::vector<std::size_t> wheels;
  for (std::size_t w = 0; w < kWheelCount; ++w) wheels.push_back(w);
  return wheels;
}

std::string fixed(double value, int digits) {
  std::ostringstream out;
  out.precision(digits);
  out << std::fixed << value;
  return out.str();
}

double rounded(double value, double per_unit) { return std::round(value * per_unit) / per_unit; }

}  // namespace marsokhod::calibration
