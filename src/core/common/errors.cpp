#include "lane_keeping/common/errors.h"

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
  for (const auto& p : problems) {
    out << "\n  - ";
    if (!p.location.empty()) out << p.location << ": ";
    if (!p.key.empty()) out << p.key << " ";
    out << p.message;
  }
  return out.str();
}

}  // namespace lane_keeping
