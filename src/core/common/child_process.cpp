#include "lane_keeping/common/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

extern char** environ;

namespace lane_keeping {
namespace {

constexpr std::size_t kErrorTail = 8192;

/// Closes the descriptors it holds when it goes out of scope.
struct Descriptors {
  int fds[4] = {-1, -1, -1, -1};
  ~Descriptors() {
    for (int fd : fds) {
      if (fd >= 0) ::close(fd);
    }
  }
};

std::string lastLines(const std::string& text, int lines) {
  std::size_t end = text.size();
  while (end > 0 && (text[end - 1] == '\n' || text[end - 1] == '\r' || text[end - 1] == ' ')) --end;
  std::size_t begin = end;
  for (int n = 0; begin > 0; --begin) {
    if (text[begin - 1] == '\n' && ++n == lines) break;
  }
  return text.substr(begin, end - begin);
}

}  // namespace

std::string ChildResult::failure() const {
  if (!started) return start_error;
  std::string why = signal != 0 ? "killed by signal " + std::to_string(signal) + " (" + strsignal(signal) + ")"
                                : "exit status " + std::to_string(exit_status);
  const std::string said = lastLines(error_output, 6);
  return said.empty() ? why + " (it wrote nothing to standard error)" : why + ": " + said;
}

ChildResult runChild(const std::vector<std::string>& argv, bool capture_output) {
  if (argv.empty()) throw std::invalid_argument("runChild: no program");
  ChildResult result;
  Descriptors d;  // [0, 1]: stderr pipe (read, write); [2, 3]: stdout pipe (read, write)
  if (::pipe2(d.fds, O_CLOEXEC) != 0 || (capture_output && ::pipe2(d.fds + 2, O_CLOEXEC) != 0)) {
    result.start_error = "cannot start " + argv[0] + ": pipe: " + std::strerror(errno);
    return result;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  if (capture_output) {
    posix_spawn_file_actions_adddup2(&actions, d.fds[3], 1);
  } else {
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  }
  posix_spawn_file_actions_adddup2(&actions, d.fds[1], 2);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  const bool search = argv[0].find('/') == std::string::npos;
  const int spawn_error = search ? posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ)
                                 : posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawn_error != 0) {
    result.start_error = "cannot start " + argv[0] + ": " + std::strerror(spawn_error);
    return result;
  }
  result.started = true;
  ::close(d.fds[1]);
  d.fds[1] = -1;
  if (capture_output) {
    ::close(d.fds[3]);
    d.fds[3] = -1;
  }
  // Both pipes drained together: a child that fills one while we wait on the other would block forever.
  std::vector<pollfd> open{{d.fds[0], POLLIN, 0}};
  if (capture_output) open.push_back({d.fds[2], POLLIN, 0});
  char buffer[4096];
  while (!open.empty()) {
    if (::poll(open.data(), open.size(), -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (std::size_t i = 0; i < open.size();) {
      if (open[i].revents == 0) {
        ++i;
        continue;
      }
      const ssize_t got = ::read(open[i].fd, buffer, sizeof(buffer));
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) {
        open.erase(open.begin() + static_cast<std::ptrdiff_t>(i));
        continue;
      }
      if (open[i].fd == d.fds[0]) {
        result.error_output.append(buffer, static_cast<std::size_t>(got));
        if (result.error_output.size() > 2 * kErrorTail) result.error_output.erase(0, result.error_output.size() - kErrorTail);
      } else {
        result.output.append(buffer, static_cast<std::size_t>(got));
      }
      open[i].revents = 0;
      ++i;
    }
  }
  if (result.error_output.size() > kErrorTail) result.error_output.erase(0, result.error_output.size() - kErrorTail);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      result.start_error = "waiting for " + argv[0] + ": " + std::strerror(errno);
      result.started = false;
      return result;
    }
  }
  if (WIFEXITED(status)) result.exit_status = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  return result;
}

}  // namespace lane_keeping
