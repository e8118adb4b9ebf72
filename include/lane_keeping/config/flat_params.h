#pragma once
/// A configuration flattened to dotted keys ("tire.front.mu") with the file and line each value
/// came from. Files are applied in order (defaults first, then overlays), then `--set key=value`
/// overrides; a later value replaces an earlier one. Sequences are leaves (waypoint lists).
#include <map>
#include <set>
#include <string>

#include <yaml-cpp/yaml.h>

namespace lane_keeping {

class FlatParams {
 public:
  struct Entry {
    YAML::Node value;      ///< scalar or sequence
    std::string location;  ///< "file.yaml:12" or "--set"
  };

  /// Parses and overlays a YAML file. Throws ConfigError naming the file (and line for syntax
  /// errors) if it is missing, unreadable, not a regular file (a directory, a device), larger than the
  /// limits of config_text_limits.h, malformed, or not a mapping at the top.
  void overlayFile(const std::string& path);
  /// Overlays YAML text (used for ROS parameter trees and tests); `origin` names it in errors.
  void overlayText(const std::string& yaml_text, const std::string& origin);
  /// Overlays an already parsed YAML mapping.
  void overlayNode(const YAML::Node& root, const std::string& origin);
  /// Applies "key=value" (value parsed as YAML, so lists work). Throws ConfigError if malformed.
  /// `origin` is the entry's location in later messages ("--set", or a runtime change's own text).
  void overlayAssignment(const std::string& assignment, const std::string& origin = "--set");
  /// Overlays another set's entries (keeping their locations), by the same replacement rule.
  void overlayFlat(const FlatParams& other);
  /// Removes every entry whose key starts with `prefix` (e.g. "log." for a section read elsewhere).
  void erasePrefix(const std::string& prefix);

  const Entry* find(const std::string& key) const;
  bool contains(const std::string& key) const { return find(key) != nullptr; }
  const std::map<std::string, Entry>& entries() const { return entries_; }
  std::string locationOf(const std::string& key) const;

 private:
  void flatten(const YAML::Node& node, const std::string& prefix, const std::string& origin);
  /// Removes the entries below `key` ("key.*").
  void eraseBelow(const std::string& key);
  /// Sets a leaf, replacing any earlier subtree at `key`.
  void setLeaf(const std::string& key, Entry entry);
  /// Stores the entry at key, replacing any there (erase and insert: see flat_params.cpp).
  void replaceLeaf(const std::string& key, Entry entry);
  std::map<std::string, Entry> entries_;
};

}  // namespace lane_keeping
