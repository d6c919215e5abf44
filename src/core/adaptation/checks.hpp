// Argument checks shared by the adaptation code. NaN and ±inf never pass: each check throws
// std::invalid_argument naming the function, the argument (and its index in a vector) and the
// value, so the caller sees which input to fix.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace marsokhod::adaptation::detail {

// Shortest round-trip text of a value ("0.0157", "nan", "-inf") for error messages.
std::string format_number(double value);

// "argument" or "argument[index]".
std::string argument_name(std::string_view argument, std::size_t index);

// Throws unless value is finite.
void require_finite(double value, std::string_view function, std::string_view argument);

// Throws unless value is finite and > 0.
void require_positive(double value, std::string_view function, std::string_view argument);

// Throws unless value is finite and ≥ 0.
void require_non_negative(double value, std::string_view function, std::string_view argument);

// Throws unless a computed value is finite: finite inputs so large that the arithmetic overflows.
void require_finite_result(double value, std::string_view function, std::string_view result);

// Throws unless value is a duty cycle: finite and in [−1, 1].
void require_duty(double value, std::string_view function, std::string_view argument);

}  // namespace marsokhod::adaptation::detail
