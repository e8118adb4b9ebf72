#include "lane_keeping/config/unique_keys.h"

#include <map>
#include <vector>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/yaml_position.h"

namespace lane_keeping {

void checkUniqueKeys(const YAML::Node& node, const std::string& origin, const std::string& prefix) {
  // Iterative, depth first: a deeply nested file must not exhaust the stack here (config_text_limits.h
  // bounds its size, not its depth's cost to a recursion).
  std::vector<std::pair<YAML::Node, std::string>> pending{{node, prefix}};
  while (!pending.empty()) {
    const auto [current, path] = pending.back();
    pending.pop_back();
    if (current.IsMap()) {
      std::map<std::string, YAML::Mark> seen;
      for (const auto& item : current) {
        if (!item.first.IsScalar()) continue;
        const std::string name = item.first.Scalar();
        const std::string key = path.empty() ? name : path + "." + name;
        const auto [first, fresh] = seen.emplace(name, item.first.Mark());
        if (!fresh) {
          throw ConfigError(std::vector<ConfigProblem>{
              {key, yamlPosition(origin, item.first.Mark()),
               "is given twice in one mapping (first at line " + std::to_string(first->second.line + 1) +
                   "): YAML keeps only one of them, without a word; merge the two into one"}});
        }
        pending.emplace_back(item.second, key);
      }
    } else if (current.IsSequence()) {
      for (std::size_t i = 0; i < current.size(); ++i) pending.emplace_back(current[i], path + "[" + std::to_string(i) + "]");
    }
  }
}

}  // namespace lane_keeping
