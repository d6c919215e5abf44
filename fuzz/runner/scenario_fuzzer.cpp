// libFuzzer target for the scenario loader (src/runner/scenario.hpp): any text loads or fails
// with std::invalid_argument naming the file — never another exception, never a crash — and a
// scenario that loads has a finite duration and finite, non-negative event times (NaN and Inf
// are refused at load time, not met in the simulator).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <string_view>

#include "runner/scenario.hpp"

namespace {

[[noreturn]] void fail(const std::string& what, std::size_t size) {
  std::fprintf(stderr, "runner_scenario_fuzzer: %s for input of %zu bytes\n", what.c_str(), size);
  std::abort();
}

bool finite_time(double t_s) { return std::isfinite(t_s) && t_s >= 0.0; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  marsokhod::runner::Scenario scenario;
  try {
    // A folder that does not exist: a terrain image the text names is never found.
    scenario = marsokhod::runner::parse_scenario(text, "/nonexistent/fuzz.toml");
  } catch (const std::invalid_argument& e) {
    if (std::string(e.what()).rfind("/nonexistent/fuzz.toml", 0) != 0) {
      fail(std::string("an error that does not name the file: ") + e.what(), size);
    }
    return 0;
  } catch (const std::exception& e) {
    fail(std::string("an exception other than invalid_argument: ") + e.what(), size);
  }
  if (!std::isfinite(scenario.duration_s) || scenario.duration_s <= 0.0) fail("bad duration", size);
  for (const auto& e : scenario.inputs) {
    if (!finite_time(e.t_s)) fail("a bad input time", size);
  }
  for (const auto& f : scenario.faults) {
    if (!finite_time(f.t_s)) fail("a bad fault time", size);
  }
  if (scenario.state_of_charge && !(*scenario.state_of_charge >= 0.0 && *scenario.state_of_charge <= 1.0)) {
    fail("a state of charge outside [0, 1]", size);
  }
  return 0;
}
