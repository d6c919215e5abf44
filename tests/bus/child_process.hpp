// Runs a program for a test with a deadline: the wait is a poll() on a pidfd, never a sleep, and
// a child that overstays is killed (by its pid) and reaped.
#pragma once

#include <signal.h>
#include <spawn.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <poll.h>
#include <unistd.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

extern char** environ;

namespace marsokhod::bus::testing {

// The exit status of the program, or nullopt when it could not start, was killed by a signal, or
// ran past `timeout` (then it is killed). stdout and stderr go to the test's own (ctest logs them).
inline std::optional<int> run_program(const std::vector<std::string>& argv,
                                      std::chrono::milliseconds timeout) {
  std::vector<char*> args;
  for (const auto& arg : argv) args.push_back(const_cast<char*>(arg.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  if (::posix_spawn(&pid, args[0], nullptr, nullptr, args.data(), environ) != 0)
    return std::nullopt;
  // The raw system call: glibc 2.36's <sys/pidfd.h> lacks extern "C" and does not link from C++.
  const int pidfd = static_cast<int>(::syscall(SYS_pidfd_open, pid, 0));
  pollfd exited{pidfd, POLLIN, 0};
  const bool in_time = pidfd >= 0 && ::poll(&exited, 1, static_cast<int>(timeout.count())) > 0;
  if (pidfd >= 0) ::close(pidfd);
  if (!in_time) ::kill(pid, SIGKILL);
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid || !in_time || !WIFEXITED(status)) return std::nullopt;
  return WEXITSTATUS(status);
}

}  // namespace marsokhod::bus::testing
