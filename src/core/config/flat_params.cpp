#include "lane_keeping/config/flat_params.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/common/file_identity.h"
#include "lane_keeping/config/config_text_limits.h"
#include "lane_keeping/config/unique_keys.h"
#include "lane_keeping/config/yaml_position.h"

namespace lane_keeping {

void FlatParams::overlayFile(const std::string& path) {
  // A directory read as "basic_filebuf::underflow", a device (/dev/zero) without end. A pipe is read (a
  // configuration from another program), bounded like any file (config_text_limits.h).
  const std::string why = whyNotRegularFile(path);
  if (why == "does not exist") throw ConfigError(path + ": cannot open configuration file (missing or unreadable)");
  if (!why.empty() && why.find("pipe") == std::string::npos) {
    throw ConfigError(path + ": cannot read it as a configuration file: it " + why);
  }
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  if (!ec && bytes > kMaxConfigBytes) {
    // Too large to read: the inline list that makes it so is named when there is one (a 97 MB file of 7
    // million waypoints), else the size.
    std::ifstream stream(path, std::ios::binary);
    checkConfigStream(stream, path);
    checkConfigBytes(bytes, path);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path + ": cannot open configuration file (missing or unreadable)");
  std::string text;
  std::vector<char> block(1 << 16);
  while (in.read(block.data(), static_cast<std::streamsize>(block.size())) || in.gcount() > 0) {
    text.append(block.data(), static_cast<std::size_t>(in.gcount()));
    checkConfigBytes(text.size(), path);  // a pipe's size is known only as it is read
  }
  if (in.bad()) throw ConfigError(path + ": cannot read the configuration file");
  overlayText(text, path);
}

void FlatParams::overlayText(const std::string& yaml_text, const std::string& origin) {
  checkConfigTextSize(yaml_text, origin);  // before yaml-cpp's nodes, about 1 kB a value
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(std::vector<ConfigProblem>{
        {"", origin + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1),
         "malformed YAML: " + e.msg}});
  }
  if (root.IsNull()) return;  // an empty overlay changes nothing
  overlayNode(root, origin);
}

void FlatParams::overlayNode(const YAML::Node& root, const std::string& origin) {
  if (!root.IsMap()) {
    throw ConfigError(std::vector<ConfigProblem>{
        {"", yamlPosition(origin, root.Mark()), "the top level must be a mapping of sections (vehicle:, tire:, ...)"}});
  }
  checkUniqueKeys(root, origin);  // yaml-cpp keeps both entries of a key given twice (unique_keys.h)
  flatten(root, "", origin);
}

void FlatParams::flatten(const YAML::Node& node, const std::string& prefix, const std::string& origin) {
  for (const auto& item : node) {
    if (!item.first.IsScalar()) {  // "? [a, b]: 1" or "{[1]: 2}": found by fuzzing (yaml-cpp's BadConversion escaped)
      throw ConfigError(std::vector<ConfigProblem>{
          {prefix, yamlPosition(origin, item.first.Mark()),
           std::string("a key must be a name, found a ") + (item.first.IsSequence() ? "list" : item.first.IsMap() ? "mapping" : "null")}});
    }
    const std::string name = item.first.as<std::string>();
    const std::string key = prefix.empty() ? name : prefix + "." + name;
    const YAML::Node& value = item.second;
    if (value.IsMap()) {
      flatten(value, key, origin);
    } else {
      setLeaf(key, Entry{value, yamlPosition(origin, value.Mark())});
    }
  }
}

void FlatParams::eraseBelow(const std::string& key) {
  // The keys "key.*" are one range of the sorted map: found in O(log n), where a scan of every entry made
  // reading n keys O(n^2) (100,000 unknown keys took over 2 minutes).
  const std::string prefix = key + ".";
  auto it = entries_.lower_bound(prefix);
  while (it != entries_.end() && it->first.compare(0, prefix.size(), prefix) == 0) it = entries_.erase(it);
}

void FlatParams::setLeaf(const std::string& key, Entry entry) {
  // A later scalar replaces any earlier subtree at the same key and vice versa.
  eraseBelow(key);
  replaceLeaf(key, std::move(entry));
}

void FlatParams::replaceLeaf(const std::string& key, Entry entry) {
  // Erased and inserted, never assigned: yaml-cpp's Node assignment rebinds the node it holds in place,
  // which every other handle on that node sees (an entry that an alias "*a" shares with another, or the
  // document's node) - entries hold their document's nodes without a clone (a lane of 1,000 inline
  // points is 3,000 nodes: cloning them was a third of the start-up, issue 18).
  entries_.erase(key);
  entries_.emplace(key, std::move(entry));
}

void FlatParams::erasePrefix(const std::string& prefix) {
  auto it = entries_.lower_bound(prefix);
  while (it != entries_.end() && it->first.compare(0, prefix.size(), prefix) == 0) it = entries_.erase(it);
}

void FlatParams::overlayFlat(const FlatParams& other) {
  for (const auto& [key, entry] : other.entries()) setLeaf(key, Entry{YAML::Clone(entry.value), entry.location});
}

void FlatParams::overlayAssignment(const std::string& assignment, const std::string& origin) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw ConfigError(origin + " '" + assignment + "': expected key=value, e.g. --set tracker.k_y=0.15");
  }
  const std::string key = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  YAML::Node value;
  try {
    value = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(origin + " " + key + ": value '" + text + "' is not valid YAML: " + e.msg);
  }
  if (value.IsMap()) {
    YAML::Node wrapper;
    wrapper[key] = value;
    // Keys given in dotted form: rebuild the nesting so flatten() sees them.
    flatten(value, key, origin);
    return;
  }
  eraseBelow(key);
  replaceLeaf(key, Entry{value, origin});
}

const FlatParams::Entry* FlatParams::find(const std::string& key) const {
  const auto it = entries_.find(key);
  return it == entries_.end() ? nullptr : &it->second;
}

std::string FlatParams::locationOf(const std::string& key) const {
  const Entry* entry = find(key);
  return entry ? entry->location : std::string();
}

}  // namespace lane_keeping
