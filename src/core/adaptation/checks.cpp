#include "core/adaptation/checks.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace marsokhod::adaptation::detail {
namespace {

[[noreturn]] void fail(std::string_view function, std::string_view argument, double value,
                       std::string_view requirement) {
  std::ostringstream message;
  message << function << ": " << argument << " = " << format_number(value) << "; " << requirement;
  throw std::invalid_argument(message.str());
}

}  // namespace

std::string format_number(double value) {
  std::array<char, 32> text{};
  const auto result = std::to_chars(text.data(), text.data() + text.size(), value);
  return std::string(text.data(), result.ptr);
}

std::string argument_name(std::string_view argument, std::size_t index) {
  return std::string(argument) + "[" + std::to_string(index) + "]";
}

void require_finite(double value, std::string_view function, std::string_view argument) {
  if (!std::isfinite(value)) {
    fail(function, argument, value, "pass a finite value");
  }
}

void require_positive(double value, std::string_view function, std::string_view argument) {
  if (!std::isfinite(value) || value <= 0.0) {
    fail(function, argument, value, "it must be finite and greater than 0");
  }
}

void require_non_negative(double value, std::string_view function, std::string_view argument) {
  if (!std::isfinite(value) || value < 0.0) {
    fail(function, argument, value, "it must be finite and not negative");
  }
}

void require_finite_result(double value, std::string_view function, std::string_view result) {
  if (!std::isfinite(value)) {
    fail(function, result, value,
         "the arithmetic overflowed: the inputs are far outside any physical range");
  }
}

void require_duty(double value, std::string_view function, std::string_view argument) {
  if (!std::isfinite(value) || std::abs(value) > 1.0) {
    fail(function, argument, value, "a duty cycle must be finite and within [-1, 1]");
  }
}

}  // namespace marsokhod::adaptation::detail
