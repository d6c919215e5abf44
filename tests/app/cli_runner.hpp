// The command line run in-process, as the tests of app/ call it: `marsokhod ARGS…` with the
// given standard input; what it printed and its exit status.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "app/cli.hpp"

namespace marsokhod::app::test {

struct Result {
  int status = 0;
  std::string out;
  std::string err;
};

inline Result cli(std::vector<const char*> args, const std::string& stdin_text = "") {
  args.insert(args.begin(), "marsokhod");
  std::istringstream in(stdin_text);
  std::ostringstream out;
  std::ostringstream err;
  const int status = run_cli(static_cast<int>(args.size()), args.data(), in, out, err);
  return {status, out.str(), err.str()};
}

}  // namespace marsokhod::app::test
