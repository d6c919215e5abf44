// Helpers shared by the behaviour tests.
#pragma once

#include "../../support/invalid_argument.hpp"

namespace marsokhod::behaviour::test {

using test_support::invalid_argument_message;
using test_support::kInf;
using test_support::kNaN;

}  // namespace marsokhod::behaviour::test
