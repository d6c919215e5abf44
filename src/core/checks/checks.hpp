// Argument checks shared by the core layers. NaN and ±inf never pass. Each check throws
// std::invalid_argument naming the function (or law, or configuration key), the argument and its
// value, and saying what to do, in one of three forms:
//   arguments of a function (adaptation, behaviour):
//     "<function>: <argument> = <value>; <requirement>"   (the value in its shortest exact form)
//   inputs of a control law (control, mobility), namespace law:
//     "<law>: <argument> must be <requirement>, got <value>; <hint>"
//   configuration values and run-time inputs of the tracking, namespace setting:
//     "invalid <name> = <value>: it must be <requirement>; <remedy>"
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>

namespace marsokhod::checks {

// Shortest round-trip text of a value ("0.0157", "nan", "-inf").
std::string format_number(double value);

// "argument" or "argument[index]".
std::string argument_name(std::string_view argument, std::size_t index);

// An element of a vector argument, "argument[index]" or with a motor's name
// "argument[index] (CL)", named only when its check fails. The element checks below run for
// every motor in every control cycle; building each name first cost the cycle more than its
// arithmetic (issue #19, BENCHMARKS.md).
struct Element {
  std::string_view argument;
  std::size_t index = 0;
  std::string_view motor = {};  // a motor's name (kMotorNames), or empty
};
std::string argument_name(const Element& element);

// The failures, out of line: the checks below are inline so that a passing check costs a
// comparison, and a name given as a `const char*` is measured only when the check fails.
namespace detail {
[[noreturn]] void fail_finite(double value, std::string_view function, std::string_view argument);
[[noreturn]] void fail_finite_estimate(double value, std::string_view function,
                                       std::string_view argument);
[[noreturn]] void fail_positive(double value, std::string_view function, std::string_view argument);
[[noreturn]] void fail_non_negative(double value, std::string_view function,
                                    std::string_view argument);
[[noreturn]] void fail_within(double value, double lowest, double highest,
                              std::string_view function, std::string_view argument);
[[noreturn]] void fail_duty(double value, std::string_view function, std::string_view argument);
[[noreturn]] void fail_finite_result(double value, std::string_view function,
                                     std::string_view result);
[[noreturn]] void fail_law_finite(double value, std::string_view law, std::string_view argument);
[[noreturn]] void fail_law_positive(double value, std::string_view law, std::string_view argument);
[[noreturn]] void fail_law_bounded(double value, double bound, std::string_view law,
                                   std::string_view argument);
}  // namespace detail

// Throws unless value is finite.
inline void require_finite(double value, std::string_view function, std::string_view argument) {
  if (!std::isfinite(value)) [[unlikely]] detail::fail_finite(value, function, argument);
}

// Throws unless value is finite, for the behaviours' inputs: estimates, whose NaN or infinity
// means the estimate feeding the behaviour is broken upstream.
inline void require_finite_estimate(double value, std::string_view function,
                                    std::string_view argument) {
  if (!std::isfinite(value)) [[unlikely]] detail::fail_finite_estimate(value, function, argument);
}

// Throws unless value is finite and > 0.
inline void require_positive(double value, std::string_view function, std::string_view argument) {
  if (!std::isfinite(value) || value <= 0.0) [[unlikely]] {
    detail::fail_positive(value, function, argument);
  }
}

// Throws unless value is finite and ≥ 0.
inline void require_non_negative(double value, std::string_view function,
                                 std::string_view argument) {
  if (!std::isfinite(value) || value < 0.0) [[unlikely]] {
    detail::fail_non_negative(value, function, argument);
  }
}

// Throws unless value is finite and within [lowest, highest].
inline void require_within(double value, double lowest, double highest, std::string_view function,
                           std::string_view argument) {
  if (!std::isfinite(value) || value < lowest || value > highest) [[unlikely]] {
    detail::fail_within(value, lowest, highest, function, argument);
  }
}

// Throws unless value is a duty cycle: finite and in [−1, 1].
inline void require_duty(double value, std::string_view function, std::string_view argument) {
  if (!std::isfinite(value) || std::abs(value) > 1.0) [[unlikely]] {
    detail::fail_duty(value, function, argument);
  }
}

// Throws unless a computed value is finite: finite inputs so large that the arithmetic overflows.
inline void require_finite_result(double value, std::string_view function,
                                  std::string_view result) {
  if (!std::isfinite(value)) [[unlikely]] detail::fail_finite_result(value, function, result);
}

// The same checks of a vector's element: the same messages, the name built only on failure.
inline void require_finite(double value, std::string_view function, const Element& argument) {
  if (!std::isfinite(value)) [[unlikely]] {
    detail::fail_finite(value, function, argument_name(argument));
  }
}
inline void require_finite_estimate(double value, std::string_view function,
                                    const Element& argument) {
  if (!std::isfinite(value)) [[unlikely]] {
    detail::fail_finite_estimate(value, function, argument_name(argument));
  }
}
inline void require_non_negative(double value, std::string_view function,
                                 const Element& argument) {
  if (!std::isfinite(value) || value < 0.0) [[unlikely]] {
    detail::fail_non_negative(value, function, argument_name(argument));
  }
}
inline void require_within(double value, double lowest, double highest, std::string_view function,
                           const Element& argument) {
  if (!std::isfinite(value) || value < lowest || value > highest) [[unlikely]] {
    detail::fail_within(value, lowest, highest, function, argument_name(argument));
  }
}
inline void require_duty(double value, std::string_view function, const Element& argument) {
  if (!std::isfinite(value) || std::abs(value) > 1.0) [[unlikely]] {
    detail::fail_duty(value, function, argument_name(argument));
  }
}
inline void require_finite_result(double value, std::string_view function,
                                  const Element& result) {
  if (!std::isfinite(value)) [[unlikely]] {
    detail::fail_finite_result(value, function, argument_name(result));
  }
}

// The inputs of a control law: every number that enters a law is checked, so that no NaN or
// infinity can leave one.
namespace law {

// Throws "<law>: <argument> must be a finite number, got <value>; <hint>" unless value is finite.
inline void require_finite(double value, std::string_view law, std::string_view argument) {
  if (!std::isfinite(value)) [[unlikely]] detail::fail_law_finite(value, law, argument);
}

// Throws unless value is finite and > 0.
inline void require_positive(double value, std::string_view law, std::string_view argument) {
  if (!std::isfinite(value) || value <= 0.0) [[unlikely]] {
    detail::fail_law_positive(value, law, argument);
  }
}

// Throws unless value is finite and |value| ≤ bound.
inline void require_bounded(double value, double bound, std::string_view law,
                            std::string_view argument) {
  if (!std::isfinite(value) || std::abs(value) > bound) [[unlikely]] {
    detail::fail_law_bounded(value, bound, law, argument);
  }
}

// require_finite of a vector's element, named only on failure.
inline void require_finite(double value, std::string_view law, const Element& argument) {
  if (!std::isfinite(value)) [[unlikely]] {
    detail::fail_law_finite(value, law, argument_name(argument));
  }
}

}  // namespace law

// Configuration values, named by their key in config/marsokhod.toml where they have one; callers
// checking run-time inputs pass their own remedy.
namespace setting {

// What to do about a bad configuration value.
inline constexpr std::string_view kConfigRemedy = "correct it in config/marsokhod.toml";

// Throws unless value is finite.
void require_finite(double value, std::string_view name, std::string_view remedy = kConfigRemedy);

// Throws unless value is finite and lies in [min, max].
void require_in_range(double value, double min, double max, std::string_view name,
                      std::string_view remedy = kConfigRemedy);

// Throws unless value is finite and strictly positive.
void require_positive(double value, std::string_view name, std::string_view remedy = kConfigRemedy);

// Throws unless value is finite and not zero.
void require_nonzero(double value, std::string_view name, std::string_view remedy = kConfigRemedy);

// Throws unless the con register value lies in 0..255 (chapter 3.2).
void require_con(int con);

}  // namespace setting

}  // namespace marsokhod::checks
