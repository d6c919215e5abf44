#include "core/control/input_checks.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace marsokhod::control {

namespace {

[[noreturn]] void reject(double value, std::string_view law, std::string_view argument,
                         std::string_view requirement, std::string_view hint) {
  std::ostringstream message;
  message << law << ": " << argument << " must be " << requirement << ", got " << value << "; "
          << hint;
  throw std::invalid_argument(message.str());
}

}  // namespace

void require_finite(double value, std::string_view law, std::string_view argument) {
  if (!std::isfinite(value)) {
    reject(value, law, argument, "a finite number",
           "a NaN or infinity here means the state estimate or the command feeding this law is "
           "broken; fix it upstream instead of passing it on");
  }
}

void require_positive(double value, std::string_view law, std::string_view argument) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    reject(value, law, argument, "a finite number > 0", "check the configuration");
  }
}

void require_bounded(double value, double bound, std::string_view law,
                     std::string_view argument) {
  require_finite(value, law, argument);
  if (std::abs(value) > bound) {
    std::ostringstream requirement;
    requirement << "within [-" << bound << ", " << bound << "]";
    reject(value, law, argument, requirement.str(),
           "Lemma 4.15 requires |c| ≤ C, so the control law that produced it is wrong");
  }
}

}  // namespace marsokhod::control
