// Test helpers for the code that rejects bad input with std::invalid_argument.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>
#include <initializer_list>
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

// Expects fn to throw std::invalid_argument whose message contains every fragment.
inline void expect_invalid_argument(const std::function<void()>& fn,
                                    std::initializer_list<std::string> fragments) {
  try {
    fn();
    ADD_FAILURE() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    for (const std::string& fragment : fragments) {
      EXPECT_THAT(error.what(), ::testing::HasSubstr(fragment));
    }
  }
}

}  // namespace marsokhod::test_support
