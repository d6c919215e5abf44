// Argument checks shared by the behaviours of chapter 6. NaN and ±inf never pass: each check
// throws std::invalid_argument "<function>: <argument> = <value>; <what to do>", so the caller
// sees which input to fix.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace marsokhod::behaviour::detail {

// "argument" or "argument[index]".
std::string argument_name(std::string_view argument, std::size_t index);

// Throws unless value is finite.
void require_finite(double value, std::string_view function, std::string_view argument);

// Throws unless value is finite and > 0.
void require_positive(double value, std::string_view function, std::string_view argument);

// Throws unless value is finite and ≥ 0.
void require_non_negative(double value, std::string_view function, std::string_view argument);

// Throws unless value is finite and within [lowest, highest].
void require_within(double value, double lowest, double highest, std::string_view function,
                    std::string_view argument);

}  // namespace marsokhod::behaviour::detail
