#include "lane_keeping/config/yaml_position.h"

namespace lane_keeping {

std::string yamlPosition(const std::string& origin, const YAML::Mark& mark) {
  return mark.line < 0 ? origin : origin + ":" + std::to_string(mark.line + 1);  // yaml-cpp counts from 0
}

}  // namespace lane_keeping
