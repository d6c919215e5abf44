// Helpers shared by the adaptation tests.
#pragma once

#include "../../support/invalid_argument.hpp"

namespace marsokhod::adaptation::test {

using test_support::invalid_argument_message;
using test_support::kInf;
using test_support::kNaN;

}  // namespace marsokhod::adaptation::test
