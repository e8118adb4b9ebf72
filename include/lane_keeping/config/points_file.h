#pragma once
/// A list of [x, y] points from a CSV file (a lane from a map: thousands of points per kilometre, which
/// as YAML take seconds to parse). One point per line, `x,y` (or separated by whitespace or ';'); an
/// optional header line and `#` comments are skipped.
#include <string>
#include <vector>

#include "lane_keeping/config/param_visitor.h"

namespace lane_keeping {

/// Largest points file read [bytes] (about 10^7 points).
constexpr long long kMaxPointsFileBytes = 512LL << 20;

/// Reads the points; on failure returns false with `error` naming the file and line. A UTF-8 byte order
/// mark before the first line is skipped; a device or a directory is refused, and so is a file or a
/// pipe of more than kMaxPointsFileBytes.
bool readPointsCsv(const std::string& path, std::vector<Point2>* points, std::string* error);

/// `path` relative to the directory of the file named in `location` ("dir/file.yaml:12"; "--set" or an
/// absolute path: as is).
std::string resolveBeside(const std::string& path, const std::string& location);

}  // namespace lane_keeping
