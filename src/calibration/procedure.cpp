// What the procedures share: --duration, the wheels they drive, the note on --motors, numbers in
// messages (procedure.hpp).
#include "calibration/procedure.hpp"

#include <sstream>
#include <stdexcept>

namespace marsokhod::calibration {

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

}  // namespace marsokhod::calibration
