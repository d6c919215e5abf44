#include "core/tracking/validation.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace marsokhod::tracking::detail {
namespace {

[[noreturn]] void reject(std::string_view name, double value, std::string_view requirement,
                         std::string_view remedy) {
  std::ostringstream message;
  message << "invalid " << name << " = " << value << ": it must be " << requirement << "; "
          << remedy;
  throw std::invalid_argument(message.str());
}

}  // namespace

void require_finite(double value, std::string_view name, std::string_view remedy) {
  if (!std::isfinite(value)) {
    reject(name, value, "a finite number", remedy);
  }
}

void require_in_range(double value, double min, double max, std::string_view name,
                      std::string_view remedy) {
  if (!std::isfinite(value) || value < min || value > max) {
    std::ostringstream requirement;
    requirement << "a finite number in [" << min << ", " << max << "]";
    reject(name, value, requirement.str(), remedy);
  }
}

void require_positive(double value, std::string_view name, std::string_view remedy) {
  if (!std::isfinite(value) || value <= 0.0) {
    reject(name, value, "a finite number above 0", remedy);
  }
}

void require_nonzero(double value, std::string_view name, std::string_view remedy) {
  if (!std::isfinite(value) || value == 0.0) {
    reject(name, value, "a finite number other than 0", remedy);
  }
}

void require_con(int con) {
  if (con < 0 || con > 255) {
    std::ostringstream message;
    message << "invalid con = " << con
            << ": the 8-bit clock register takes 0..255; configure cycle.con within that range";
    throw std::invalid_argument(message.str());
  }
}

}  // namespace marsokhod::tracking::detail
