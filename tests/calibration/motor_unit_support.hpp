// Shared by the motor procedures' tests (motor-curve, motor-scale, response, load, the load
// tracking test): a simulated unit drawn from a seed, kept fixed while the driver's configuration
// changes (SimOptions::unit), and the configuration after Procedure 3.5 on it (its true supply
// conversion, so that U is measured right and the motor procedures are judged on their own), and
// the procedures run in turn on it.
#pragma once

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <cstdint>
#include <filesystem>
#include <vector>

#include "calibration/bench.hpp"
#include "calibration/procedures.hpp"
#include "calibration_test_support.hpp"
#include "config/calibration.hpp"
#include "config/load_params.hpp"
#include "core/params.hpp"
#include "sim/electrics/motor_model.hpp"
#include "sim/electrics/sim_truth.hpp"
#include "sim/rover/simulated_rover.hpp"

namespace marsokhod::calibration::testing {

inline std::filesystem::path config_file() { return kConfigFile; }

struct TestUnit {
  std::uint64_t seed = 0;
  sim::SimTruth truth;
  Params params;  // the configuration, with the unit's supply conversion (Procedure 3.5 done)
};

inline TestUnit drawn_unit(std::uint64_t seed) {
  TestUnit unit;
  unit.seed = seed;
  const Params nominal = config::load_params(config_file());
  unit.truth = sim::make_sim_truth(nominal, seed);
  unit.params = nominal;
  unit.params.sensors.supply = unit.truth.sensors.supply;
  return unit;
}

// The laboratory (tether, flat ground) with exactly this unit.
inline sim::SimOptions unit_options(const TestUnit& unit) {
  sim::SimOptions options = sim_bench_options(unit.seed);
  options.unit = unit.truth;
  return options;
}

// Adds `from`'s sections to `into` (arrays of tables appended, tables merged key by key).
inline void merge_values(toml::table& into, const toml::table& from) {
  for (const auto& [key, node] : from) {
    if (const toml::table* t = node.as_table()) {
      if (toml::table* existing = into[key].as_table()) {
        for (const auto& [k, v] : *t) existing->insert_or_assign(k, v);
        continue;
      }
    } else if (const toml::array* a = node.as_array()) {
      if (toml::array* existing = into[key].as_array()) {
        for (const auto& v : *a) existing->push_back(v);
        continue;
      }
    }
    into.insert_or_assign(key, node);
  }
}

// The Params the values give on top of the configuration, for this unit (supply conversion kept).
inline Params apply_values(const TestUnit& unit, const toml::table& values) {
  Params params = config::apply_calibration_values(config_file(), values);
  params.sensors.supply = unit.truth.sensors.supply;
  return params;
}

// The procedure of that name with --duration on the unit's laboratory bench, the driver
// configured by `params` (by unit.params when not given).
inline ProcedureResult calibrate_unit(const TestUnit& unit, const Params& params,
                                      const std::string& procedure, double duration_s) {
  SimBench bench(params, unit_options(unit));
  ProcedureOptions options;
  options.duration_s = duration_s;
  return run_procedure(bench, procedure, options);
}

inline ProcedureResult calibrate_unit(const TestUnit& unit, const std::string& procedure,
                                      double duration_s) {
  return calibrate_unit(unit, unit.params, procedure, duration_s);
}

// One procedure of a chain and how long it runs (--duration).
struct ChainStep {
  std::string procedure;
  double duration_s = 0.0;
};

// Runs the steps in turn on the unit, each with the configuration the values before it give
// (the first with unit.params), and merges every step's values into `values`. Fails fatally at
// the first refused fit: call it in ASSERT_NO_FATAL_FAILURE.
inline void calibrate_in_turn(const TestUnit& unit, const std::vector<ChainStep>& steps,
                              toml::table& values) {
  for (const ChainStep& step : steps) {
    const Params params = values.empty() ? unit.params : apply_values(unit, values);
    const ProcedureResult result = calibrate_unit(unit, params, step.procedure, step.duration_s);
    ASSERT_TRUE(result.accepted()) << result.procedure << ": " << result.problems.front();
    merge_values(values, result.values);
  }
}

// The unit's true no-load speed of motor i at d, Ū = 24 V [rad/s].
inline double true_speed(const TestUnit& unit, std::size_t motor, double duty, int icr = 511) {
  return sim::steady_no_load_speed_radps(unit.truth.motors[motor], duty, 24.0, icr);
}

}  // namespace marsokhod::calibration::testing
