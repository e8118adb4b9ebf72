#include "lane_keeping/common/errors.h"

#include <algorithm>
#include <sstream>

namespace lane_keeping {

ConfigError::ConfigError(std::vector<ConfigProblem> problems)
    : LaneKeepingError(render(problems)), problems_(std::move(problems)) {}

ConfigError::ConfigError(const std::string& single_message)
    : LaneKeepingError("invalid configuration: " + single_message),
      problems_{ConfigProblem{"", "", single_message}} {}

std::string ConfigError::render(const std::vector<ConfigProblem>& problems) {
  std::ostringstream out;
  out << "invalid configuration (" << problems.size() << (problems.size() == 1 ? " problem" : " problems") << "):";
  // The first ones, then a count: 100,000 unknown keys printed one by one buried the message (all of
  // them stay in problems()).
  const std::size_t shown = std::min(problems.size(), kProblemsShown);
  for (std::size_t i = 0; i < shown; ++i) {
    const ConfigProblem& p = problems[i];
    out << "\n  - ";
    if (!p.location.empty()) out << p.location << ": ";
    if (!p.key.empty()) out << p.key << " ";
    out << p.message;
  }
  if (shown < problems.size()) {
    const std::size_t more = problems.size() - shown;
    out << "\n  ... and " << more << " more " << (more == 1 ? "problem" : "problems") << " not shown";
  }
  return out.str();
}

}  // namespace lane_keeping
