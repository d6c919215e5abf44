#include "runner/child_processes.hpp"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>

extern char** environ;

namespace marsokhod::runner {
namespace {

struct Running {
  std::size_t index = 0;
  pid_t pid = -1;
  std::array<int, 2> fds{-1, -1};  // read ends of the child's stdout and stderr
};

void close_fd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

// Starts jobs[index]; on failure the outcome says why and nothing is left running.
bool start(const std::vector<std::string>& argv, std::size_t index, Running& child,
           ChildOutcome& outcome) {
  int out_pipe[2] = {-1, -1};
  int err_pipe[2] = {-1, -1};
  if (::pipe2(out_pipe, O_CLOEXEC) != 0 || ::pipe2(err_pipe, O_CLOEXEC) != 0) {
    outcome.err = std::string("cannot make a pipe: ") + std::strerror(errno);
    for (int fd : {out_pipe[0], out_pipe[1], err_pipe[0], err_pipe[1]}) if (fd >= 0) ::close(fd);
    return false;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, out_pipe[1], 1);
  posix_spawn_file_actions_adddup2(&actions, err_pipe[1], 2);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  const int status = ::posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(out_pipe[1]);
  ::close(err_pipe[1]);
  if (status != 0) {
    ::close(out_pipe[0]);
    ::close(err_pipe[0]);
    outcome.err = "cannot start '" + argv[0] + "': " + std::strerror(status);
    return false;
  }
  child = Running{index, pid, {out_pipe[0], err_pipe[0]}};
  outcome.started = true;
  return true;
}

void finish(Running& child, ChildOutcome& outcome) {
  int status = 0;
  while (::waitpid(child.pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status)) outcome.exit_status = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) outcome.signal = WTERMSIG(status);
}

}  // namespace

std::vector<ChildOutcome> run_children(
    const std::vector<std::vector<std::string>>& jobs, std::size_t parallel,
    const std::function<void(std::size_t, const ChildOutcome&)>& on_done) {
  if (parallel == 0) throw std::invalid_argument("run_children: parallel must be at least 1");
  std::vector<ChildOutcome> outcomes(jobs.size());
  std::vector<Running> running;
  std::size_t next = 0;
  const auto done = [&](std::size_t index) {
    if (on_done) on_done(index, outcomes[index]);
  };
  while (next < jobs.size() || !running.empty()) {
    while (next < jobs.size() && running.size() < parallel) {
      Running child;
      if (jobs[next].empty()) {
        outcomes[next].err = "empty command line";
        done(next);
      } else if (start(jobs[next], next, child, outcomes[next])) {
        running.push_back(child);
      } else {
        done(next);
      }
      ++next;
    }
    if (running.empty()) continue;
    std::vector<pollfd> fds;
    for (const Running& c : running) {
      for (int fd : c.fds) fds.push_back({fd, fd >= 0 ? short(POLLIN) : short(0), 0});
    }
    if (::poll(fds.data(), fds.size(), -1) < 0 && errno != EINTR) {
      throw std::runtime_error(std::string("run_children: poll: ") + std::strerror(errno));
    }
    char buffer[65536];
    for (std::size_t i = 0; i < fds.size(); ++i) {
      if (fds[i].fd < 0 || fds[i].revents == 0) continue;
      Running& c = running[i / 2];
      const ssize_t n = ::read(fds[i].fd, buffer, sizeof buffer);
      if (n > 0) {
        (i % 2 == 0 ? outcomes[c.index].out : outcomes[c.index].err).append(buffer, n);
      } else if (n == 0 || errno != EINTR) {
        close_fd(c.fds[i % 2]);
      }
    }
    for (auto it = running.begin(); it != running.end();) {
      if (it->fds[0] >= 0 || it->fds[1] >= 0) {
        ++it;
        continue;
      }
      finish(*it, outcomes[it->index]);
      const std::size_t index = it->index;
      it = running.erase(it);
      done(index);
    }
  }
  return outcomes;
}

}  // namespace marsokhod::runner
