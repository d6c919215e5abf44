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

#include "../../support/invalid_argument.hpp"
#include "core/params.hpp"

namespace marsokhod::mobility::testing {

using test_support::kNaN;
inline constexpr double kInfinity = test_support::kInf;

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

using test_support::expect_invalid_argument;

}  // namespace marsokhod::mobility::testing
