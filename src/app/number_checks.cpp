#include "app/number_checks.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace marsokhod::app {
namespace {

// The text as a finite number, or a message saying why not.
std::string parse_finite(const std::string& text, double& value) {
  const char* begin = text.c_str();
  char* end = nullptr;
  value = std::strtod(begin, &end);  // overflow gives ±HUGE_VAL, underflow a number near 0
  // As CLI11 converts it afterwards: the whole text, no spaces around it.
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front())) != 0 ||
      end != begin + text.size()) {
    return text + " is not a number";
  }
  if (!std::isfinite(value)) return text + " is not a finite number";
  return {};
}

std::string bound(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

CLI::Validator finite_check(double min, bool min_open, double max, const std::string& what) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double value = 0.0;
        if (std::string why = parse_finite(text, value); !why.empty()) return why + "; " + what;
        const bool below = min_open ? !(value > min) : !(value >= min);
        if (below || !(value <= max)) return text + " is out of range; " + what;
        return {};
      },
      what);
}

}  // namespace

CLI::Validator finite_range(double min, double max) {
  return finite_check(min, false, max, "a number in [" + bound(min) + ", " + bound(max) + "]");
}

CLI::Validator finite_positive() {
  return finite_check(0.0, true, HUGE_VAL, "a finite number > 0");
}

CLI::Validator finite_non_negative() {
  return finite_check(0.0, false, HUGE_VAL, "a finite number ≥ 0");
}

}  // namespace marsokhod::app
