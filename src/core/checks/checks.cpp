#include "core/checks/checks.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace marsokhod::checks {
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

std::string argument_name(const Element& element) {
  std::string name = argument_name(element.argument, element.index);
  if (!element.motor.empty()) name += " (" + std::string(element.motor) + ")";
  return name;
}

namespace detail {
namespace {

[[noreturn]] void reject_law(double value, std::string_view law, std::string_view argument,
                             std::string_view requirement, std::string_view hint) {
  std::ostringstream message;
  message << law << ": " << argument << " must be " << requirement << ", got " << value << "; "
          << hint;
  throw std::invalid_argument(message.str());
}

}  // namespace

void fail_finite(double value, std::string_view function, std::string_view argument) {
  fail(function, argument, value, "pass a finite value");
}

void fail_finite_estimate(double value, std::string_view function, std::string_view argument) {
  fail(function, argument, value,
       "pass a finite value (a NaN or infinity means the estimate feeding this behaviour is "
       "broken upstream)");
}

void fail_positive(double value, std::string_view function, std::string_view argument) {
  fail(function, argument, value, "it must be finite and greater than 0");
}

void fail_non_negative(double value, std::string_view function, std::string_view argument) {
  fail(function, argument, value, "it must be finite and not negative");
}

void fail_within(double value, double lowest, double highest, std::string_view function,
                 std::string_view argument) {
  fail(function, argument, value,
       "it must be finite and within [" + format_number(lowest) + ", " + format_number(highest) +
           "]");
}

void fail_duty(double value, std::string_view function, std::string_view argument) {
  fail(function, argument, value, "a duty cycle must be finite and within [-1, 1]");
}

void fail_finite_result(double value, std::string_view function, std::string_view result) {
  fail(function, result, value,
       "the arithmetic overflowed: the inputs are far outside any physical range");
}

void fail_law_finite(double value, std::string_view law, std::string_view argument) {
  reject_law(value, law, argument, "a finite number",
             "a NaN or infinity here means the state estimate or the command feeding this law is "
             "broken; fix it upstream instead of passing it on");
}

void fail_law_positive(double value, std::string_view law, std::string_view argument) {
  reject_law(value, law, argument, "a finite number > 0", "check the configuration");
}

void fail_law_bounded(double value, double bound, std::string_view law,
                      std::string_view argument) {
  if (!std::isfinite(value)) fail_law_finite(value, law, argument);
  std::ostringstream requirement;
  requirement << "within [-" << bound << ", " << bound << "]";
  reject_law(value, law, argument, requirement.str(),
             "Lemma 4.15 requires |c| ≤ C, so the control law that produced it is wrong");
}

}  // namespace detail

namespace setting {
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

}  // namespace setting

}  // namespace marsokhod::checks
