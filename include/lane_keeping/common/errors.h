#pragma once
/// Typed exceptions of the core. Wrappers (tools, nodes) catch them at the boundary and stop
/// with the message (nonzero exit, or fatal log + shutdown); the core never clamps silently.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace lane_keeping {

/// Base of every error the core throws on purpose.
class LaneKeepingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One problem in a configuration: the full dotted key, where it came from, and why.
struct ConfigProblem {
  std::string key;       ///< e.g. "vehicle.mass"
  std::string location;  ///< e.g. "config/fig6.yaml:12", or "" if unknown
  std::string message;   ///< e.g. "= -3 kg, must be > 0"
};

/// Invalid configuration. Carries *all* problems found, not just the first; its message lists the
/// first kProblemsShown and says how many more there are.
class ConfigError : public LaneKeepingError {
 public:
  static constexpr std::size_t kProblemsShown = 20;

  explicit ConfigError(std::vector<ConfigProblem> problems);
  explicit ConfigError(const std::string& single_message);
  const std::vector<ConfigProblem>& problems() const { return problems_; }

 private:
  static std::string render(const std::vector<ConfigProblem>& problems);
  std::vector<ConfigProblem> problems_;
};

/// Bad input data (log files, bags, CSV): names the file, line/row or topic.
class InputError : public LaneKeepingError {
 public:
  using LaneKeepingError::LaneKeepingError;
};

/// A model evaluation produced a non-finite value or left its domain (e.g. |delta| >= pi/2).
class ModelError : public LaneKeepingError {
 public:
  using LaneKeepingError::LaneKeepingError;
};

/// A command-line argument the tool cannot take (a number that is not one, out of its range, an output
/// that is one of the inputs): tools print it with their usage and exit with status 2.
class UsageError : public LaneKeepingError {
 public:
  using LaneKeepingError::LaneKeepingError;
};

/// The lockstep schedule cannot advance: the loop's delays give no lookahead.
class ScheduleError : public LaneKeepingError {
 public:
  using LaneKeepingError::LaneKeepingError;
};

}  // namespace lane_keeping
