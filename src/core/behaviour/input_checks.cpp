#include "core/behaviour/input_checks.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace marsokhod::behaviour::detail {
namespace {

// Shortest round-trip text of a value ("0.0157", "nan", "-inf").
std::string format_number(double value) {
  std::array<char, 32> text{};
  const auto result = std::to_chars(text.data(), text.data() + text.size(), value);
  return std::string(text.data(), result.ptr);
}

[[noreturn]] void fail(std::string_view function, std::string_view argument, double value,
                       std::string_view requirement) {
  std::ostringstream message;
  message << function << ": " << argument << " = " << format_number(value) << "; " << requirement;
  throw std::invalid_argument(message.str());
}

}  // namespace

std::string argument_name(std::string_view argument, std::size_t index) {
  return std::string(argument) + "[" + std::to_string(index) + "]";
}

void require_finite(double value, std::string_view function, std::string_view argument) {
  if (!std::isfinite(value)) {
    fail(function, argument, value,
         "pass a finite value (a NaN or infinity means the estimate feeding this behaviour is "
         "broken upstream)");
  }
}

void require_positive(double value, std::string_view function, std::string_view argument) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    fail(function, argument, value, "it must be finite and greater than 0");
  }
}

void require_non_negative(double value, std::string_view function, std::string_view argument) {
  if (!std::isfinite(value) || value < 0.0) {
    fail(function, argument, value, "it must be finite and not negative");
  }
}

void require_within(double value, double lowest, double highest, std::string_view function,
                    std::string_view argument) {
  if (!std::isfinite(value) || value < lowest || value > highest) {
    fail(function, argument, value,
         "it must be finite and within [" + format_number(lowest) + ", " + format_number(highest) +
             "]");
  }
}

}  // namespace marsokhod::behaviour::detail
