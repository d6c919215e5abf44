// Test helpers for the mobility layer: the thesis' parameters, a check for std::invalid_argument
// and a central finite difference.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>
#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/params.hpp"

namespace marsokhod::mobility::testing {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The chapter 3.1 geometry with the wheel radius r [m] (0.125 on solid ground, 0.115 on sand).
inline GeometryParams geometry_with_radius(double wheel_radius_m) {
  GeometryParams geometry;
  geometry.wheel_radius_m = wheel_radius_m;
  return geometry;
}

// (f(x + h) − f(x − h))/(2h): error O(h²·f''') — 1e-10 for h = 1e-5 on these smooth functions.
inline double central_difference(const std::function<double(double)>& f, double x,
                                 double step = 1e-5) {
  return (f(x + step) - f(x - step)) / (2.0 * step);
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

}  // namespace marsokhod::mobility::testing
