#pragma once
/// A key given twice in one YAML mapping is refused (issue 48: found by the log_mapping fuzz target).
/// YAML requires a mapping's keys to be unique, but yaml-cpp keeps both entries: iterating sees both (the
/// configuration's reader kept the last: two `vehicle:` sections set the mass of the second, the first
/// was dropped without a word), a lookup the first (the log mapping's reader read the first `columns:`,
/// the configuration's reader refused a key of the second). Either way the file does not say what its
/// author meant; the error names both lines.
#include <string>

#include <yaml-cpp/yaml.h>

namespace lane_keeping {

/// Throws ConfigError naming `origin`:line and the dotted key (below `prefix`) of the first name that a
/// mapping in `node`'s tree (mappings and lists, at any depth) holds twice, with the line of its first
/// occurrence. Keys that are not names (lists, mappings, null) are left to the readers, which refuse them.
void checkUniqueKeys(const YAML::Node& node, const std::string& origin, const std::string& prefix = "");

}  // namespace lane_keeping
