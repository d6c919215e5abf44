// Test helpers for the layers that reject bad input with std::invalid_argument.
#pragma once

#include <limits>
#include <stdexcept>
#include <string>

namespace marsokhod::test_support {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();

// The message of the std::invalid_argument that call throws, or a marker the assertion shows.
template <class Call>
std::string invalid_argument_message(Call&& call) {
  try {
    call();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "<no std::invalid_argument thrown>";
}

}  // namespace marsokhod::test_support
