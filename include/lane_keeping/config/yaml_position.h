#pragma once
/// Where in a YAML file something is, as every error message of the readers names it: "file:line", or the
/// file alone where yaml-cpp has no position (a node built in memory, `--set`).
#include <string>

#include <yaml-cpp/mark.h>

namespace lane_keeping {

std::string yamlPosition(const std::string& origin, const YAML::Mark& mark);

}  // namespace lane_keeping
