// Checks for the command line's real-valued options. CLI11's Range, PositiveNumber and
// NonNegativeNumber compare the parsed number with their bounds, and every comparison with NaN is
// false, so "--duration nan" or "--distance nan" passed them: a run without an end, a sweep that
// counted nothing as climbed. These refuse anything that is not a finite number in the bounds,
// with the bounds in the message.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace marsokhod::app {

// A finite number in [min, max].
CLI::Validator finite_range(double min, double max);
// A finite number > 0.
CLI::Validator finite_positive();
// A finite number ≥ 0.
CLI::Validator finite_non_negative();

}  // namespace marsokhod::app
