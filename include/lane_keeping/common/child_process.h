#pragma once
/// Running another program from a tool (the plotting scripts): started from its argument vector with
/// posix_spawn, never through a shell. A report directory named `x';touch F;'` was pasted into a shell
/// command line and ran `touch F`; one named `O'Brien runs` broke the quoting, and the failure was
/// reported as a missing python3-matplotlib. Here an argument is one argument whatever it holds, and a
/// failure says what the child said.
#include <string>
#include <vector>

namespace lane_keeping {

struct ChildResult {
  bool started = false;       ///< false: the program could not be started (`start_error` says why)
  std::string start_error;
  int exit_status = -1;       ///< its exit status, when it exited
  int signal = 0;             ///< the signal that ended it, or 0
  std::string output;         ///< its standard output, when captured
  std::string error_output;   ///< the end of its standard error (at most the last 8 kB)

  bool ok() const { return started && signal == 0 && exit_status == 0; }
  /// Why it failed, for a message: "cannot start /usr/bin/python3: No such file or directory", or
  /// "exit status 1: <the last lines of its standard error>", or "killed by signal 9".
  std::string failure() const;
};

/// Runs argv[0] (a path; without a '/', looked up on PATH) with the arguments argv[1..], standard input
/// from /dev/null, standard output captured into `output` if `capture_output` (else discarded), standard
/// error captured; waits for it. Throws std::invalid_argument for an empty argv.
ChildResult runChild(const std::vector<std::string>& argv, bool capture_output = false);

}  // namespace lane_keeping
