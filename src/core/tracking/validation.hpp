// Argument checks shared by the tracking code. Every message names the offending parameter (by
// its key in config/marsokhod.toml where it has one) and says how to fix it.
#pragma once

#include <string_view>

namespace marsokhod::tracking::detail {

// What to do about a bad configuration value; callers checking run-time inputs pass their own.
inline constexpr std::string_view kConfigRemedy = "correct it in config/marsokhod.toml";

// Throws std::invalid_argument unless value is finite.
void require_finite(double value, std::string_view name, std::string_view remedy = kConfigRemedy);

// Throws std::invalid_argument unless value is finite and lies in [min, max].
void require_in_range(double value, double min, double max, std::string_view name,
                      std::string_view remedy = kConfigRemedy);

// Throws std::invalid_argument unless value is finite and strictly positive.
void require_positive(double value, std::string_view name, std::string_view remedy = kConfigRemedy);

// Throws std::invalid_argument unless value is finite and not zero.
void require_nonzero(double value, std::string_view name, std::string_view remedy = kConfigRemedy);

// Throws std::invalid_argument unless the con register value lies in 0..255 (chapter 3.2).
void require_con(int con);

}  // namespace marsokhod::tracking::detail
