#include "lane_keeping/config/points_file.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>

namespace lane_keeping {
namespace {

bool separatorOrEnd(char c) { return c == '\0' || c == ',' || c == ';' || c == ' ' || c == '\t'; }

/// Parses a number at *p, skipping separators after it; false if none. std::from_chars first (a lane from
/// a map has 10^5 lines: strtod's locale handling was a third of reading them), strtod for what it alone
/// takes (leading blanks or '+', hexadecimal): the same numbers, correctly rounded either way.
bool number(const char** p, double* value) {
  const char* text = *p;
  const auto [ptr, ec] = std::from_chars(text, text + std::strlen(text), *value);
  const char* end = ptr;
  if (ec != std::errc() || ptr == text || !separatorOrEnd(*ptr)) {
    char* strtod_end = nullptr;
    errno = 0;
    *value = std::strtod(text, &strtod_end);
    if (strtod_end == text || errno == ERANGE) return false;
    end = strtod_end;
  }
  if (!std::isfinite(*value)) return false;
  *p = end;
  while (**p == ',' || **p == ';' || **p == ' ' || **p == '\t') ++*p;
  return true;
}

}  // namespace

bool readPointsCsv(const std::string& path, std::vector<Point2>* points, std::string* error) {
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot open the points file (" + std::strerror(errno) + ")";
    return false;
  }
  points->clear();
  std::string line;
  for (int number_of_line = 1; std::getline(in, line); ++number_of_line) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    const char* p = line.c_str() + first;
    Point2 point{0.0, 0.0};
    if (!number(&p, &point[0]) || !number(&p, &point[1]) || *p != '\0') {
      if (points->empty() && std::isalpha(static_cast<unsigned char>(line[first]))) continue;  // a header
      *error = path + ":" + std::to_string(number_of_line) + ": expected 'x,y' (two finite numbers), got '" + line + "'";
      return false;
    }
    points->push_back(point);
  }
  if (points->empty()) {
    *error = path + ": no points in the file";
    return false;
  }
  return true;
}

std::string resolveBeside(const std::string& path, const std::string& location) {
  if (path.empty() || path[0] == '/') return path;
  const std::size_t colon = location.rfind(':');
  const std::string file = colon == std::string::npos ? location : location.substr(0, colon);
  const std::size_t slash = file.rfind('/');
  if (file.empty() || file == "--set" || slash == std::string::npos) return path;
  return file.substr(0, slash + 1) + path;
}

}  // namespace lane_keeping
