// Runs programs as child processes, a few at a time, and collects what each printed: how a sweep
// spreads its runs over the machine's cores. A run that crashes is then one failed run, not the
// end of the sweep, and no run shares memory (or MuJoCo's loader) with another.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace marsokhod::runner {

struct ChildOutcome {
  bool started = false;  // false: the program could not be started (see err)
  int exit_status = -1;  // the exit status, when it exited
  int signal = 0;        // the signal that ended it, when one did
  std::string out;       // its standard output
  std::string err;       // its standard error
  bool exited_cleanly() const { return started && signal == 0 && exit_status >= 0; }
};

// Runs every argv (argv[0] is the program's path), at most `parallel` (≥ 1) at once, in the order
// given; `on_done(index, outcome)` is called in the calling thread as each one ends. Returns the
// outcomes in the order of `jobs`. Standard input of the children is /dev/null.
std::vector<ChildOutcome> run_children(
    const std::vector<std::vector<std::string>>& jobs, std::size_t parallel,
    const std::function<void(std::size_t, const ChildOutcome&)>& on_done = {});

}  // namespace marsokhod::runner
