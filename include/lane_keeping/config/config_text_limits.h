#pragma once
/// Limits on a configuration's text, checked before yaml-cpp builds its nodes. yaml-cpp keeps about a
/// kilobyte per value: a 97 MB YAML file of 7 million inline waypoints ended in std::bad_alloc at 7.9 GB,
/// naming neither file nor key. A configuration holds a few hundred values; a lane of 10^5 points inline
/// is the largest in use (docs/benchmarks.md) and a longer one belongs in a CSV file
/// (`path.waypoints: lane.csv`), which is read without yaml-cpp.
#include <cstddef>
#include <istream>
#include <string>

namespace lane_keeping {

/// Largest configuration file read [bytes].
constexpr std::size_t kMaxConfigBytes = std::size_t{64} << 20;
/// Largest inline list (values and sub-lists counted): 200,000 points [x, y], about 250 MB parsed.
constexpr std::size_t kMaxInlineListValues = 600000;
/// Most values in one configuration text (keys and values counted), about 1 GB parsed.
constexpr std::size_t kMaxConfigValues = 1000000;
/// Texts up to this size are not scanned (nor texts with fewer separators than kMaxInlineListValues):
/// they cannot hold more than about 500,000 values.
constexpr std::size_t kConfigScanFromBytes = std::size_t{1} << 20;

/// Throws ConfigError naming `origin` if `bytes` exceeds kMaxConfigBytes.
void checkConfigBytes(std::size_t bytes, const std::string& origin);

/// Throws ConfigError naming `origin` (file:line) and the key if `yaml_text` is larger than
/// kMaxConfigBytes, holds an inline list of more than kMaxInlineListValues values, or more than
/// kMaxConfigValues values in all. Streams the text through yaml-cpp's event parser, which builds no
/// nodes, and stops at the first list over its limit. Malformed YAML is left to the parse that follows.
void checkConfigTextSize(const std::string& yaml_text, const std::string& origin);
/// The same scan, streamed from `in` (a file too large to read whole: the list that makes it so is named).
void checkConfigStream(std::istream& in, const std::string& origin);

}  // namespace lane_keeping
