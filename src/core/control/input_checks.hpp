// Input guards shared by the control laws: every number that enters a law is checked here, so
// that no NaN or infinity can leave one. A law names itself and the offending argument.
#pragma once

#include <string_view>

namespace marsokhod::control {

// Throws std::invalid_argument "<law>: <argument> must be a finite number, got <value>; <hint>"
// unless value is finite.
void require_finite(double value, std::string_view law, std::string_view argument);

// Throws std::invalid_argument unless value is finite and > 0.
void require_positive(double value, std::string_view law, std::string_view argument);

// Throws std::invalid_argument unless value is finite and |value| ≤ bound.
void require_bounded(double value, double bound, std::string_view law, std::string_view argument);

}  // namespace marsokhod::control
