#include "lane_keeping/config/points_file.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <vector>

#include "lane_keeping/common/file_identity.h"
#include "lane_keeping/common/fresh_memory.h"

namespace lane_keeping {
namespace {

bool separatorOrEnd(char c) { return c == '\0' || c == ',' || c == ';' || c == ' ' || c == '\t'; }

/// Parses a number at *p, skipping separators after it; false if none. std::from_chars first (a lane from
/// a map has 10^5 lines: strtod's locale handling was a third of reading them), strtod for what it alone
/// takes (leading blanks or '+', hexadecimal): the same numbers, correctly rounded either way. The text
/// ends at `end`, where a '\0' is.
bool number(const char** p, const char* end_of_line, double* value) {
  const char* text = *p;
  const auto [ptr, ec] = std::from_chars(text, end_of_line, *value);
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

/// The line as a message shows it: bytes that do not print (a stray BOM, control characters) as \xNN.
std::string visible(const char* text, const char* end) {
  std::string out;
  for (const char* p = text; p < end; ++p) {
    const auto c = static_cast<unsigned char>(*p);
    if (c < 0x20 || c >= 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof(hex), "\\x%02X", c);
      out += hex;
    } else {
      out += *p;
    }
  }
  return out;
}

}  // namespace

bool readPointsCsv(const std::string& path, std::vector<Point2>* points, std::string* error) {
  // A device (path.waypoints: /dev/zero) was read without end, and a directory as an empty file. A pipe
  // is read (a lane from another program), bounded below like any file.
  const std::string why = whyNotRegularFile(path);
  if (!why.empty() && why != "does not exist" && why.find("pipe") == std::string::npos) {
    *error = path + ": cannot read it as a points file: it " + why;
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    *error = path + ": cannot open the points file (" + std::strerror(errno) + ")";
    return false;
  }
  const std::string too_large = path + ": more than " + std::to_string(kMaxPointsFileBytes >> 20) +
                                " MB; a points file is at most that (about 10^7 points)";
  in.seekg(0, std::ios::end);
  if (in && static_cast<long long>(in.tellg()) > kMaxPointsFileBytes) {
    *error = too_large;
    return false;
  }
  in.clear();
  in.seekg(0, std::ios::beg);
  points->clear();
  // Room for every line of the file, mapped in one call (fresh_memory.h): growing by doubling wrote each
  // point up to twice and faulted in twice the pages - a third of reading 10^5 points (issue 18). Lines
  // are counted in a first pass where the file can be read twice (not a pipe).
  in.seekg(0, std::ios::end);
  const bool seekable = static_cast<bool>(in);
  in.clear();
  in.seekg(0, std::ios::beg);
  if (seekable) {
    std::size_t lines = 1;
    std::vector<char> block(1 << 16);
    while (in.read(block.data(), static_cast<std::streamsize>(block.size())) || in.gcount() > 0) {
      lines += static_cast<std::size_t>(std::count(block.data(), block.data() + in.gcount(), '\n'));
    }
    in.clear();
    in.seekg(0, std::ios::beg);
    // At most 2^22 points (64 MB) reserved and mapped ahead: a hostile file of gigabytes of blank lines would
    // otherwise map gigabytes before a line is parsed. A longer lane grows as a vector does.
    const std::size_t room = std::min<std::size_t>(lines, std::size_t{1} << 22);
    points->reserve(room);
    populatePages(points->data(), room * sizeof(Point2));
  }
  in.clear();
  // One line: a point, a blank line, a comment or (before the first point) a header; false with the
  // error otherwise. The line is [text, end), with a '\0' at end.
  auto line = [&](char* text, char* end, int number_of_line) {
    if (end > text && end[-1] == '\r') *--end = '\0';
    // A UTF-8 byte order mark, as spreadsheet programs write one, before the first line.
    if (number_of_line == 1 && end - text >= 3 && std::memcmp(text, "\xEF\xBB\xBF", 3) == 0) text += 3;
    const char* p = text;
    while (p < end && (*p == ' ' || *p == '\t')) ++p;
    if (p == end || *p == '#') return true;
    const char first = *p;
    Point2 point{0.0, 0.0};
    if (!number(&p, end, &point[0]) || !number(&p, end, &point[1]) || *p != '\0') {
      if (points->empty() && std::isalpha(static_cast<unsigned char>(first))) return true;  // a header
      *error = path + ":" + std::to_string(number_of_line) + ": expected 'x,y' (two finite numbers), got '" +
               visible(text, end) + "'";
      return false;
    }
    points->push_back(point);
    return true;
  };
  // The lines are parsed where they lie in a block of the file (getline's copy of each, and a strlen per
  // number, were half of reading 10^5 points); a line cut by the block's end moves to its start and is
  // completed by the next read.
  std::vector<char> block(1 << 16);
  std::size_t kept = 0;  // bytes of a cut line at the block's start
  int number_of_line = 0;
  long long total = 0;  // a pipe's size is known only as it is read
  for (;;) {
    if (kept + 1 >= block.size()) block.resize(2 * block.size());  // a line longer than the block
    in.read(block.data() + kept, static_cast<std::streamsize>(block.size() - 1 - kept));  // one byte spare
    const std::size_t got = static_cast<std::size_t>(in.gcount());
    total += static_cast<long long>(got);
    if (total > kMaxPointsFileBytes) {
      *error = too_large;
      return false;
    }
    const bool at_end = got == 0;
    char* begin = block.data();
    char* const stop = begin + kept + got;
    while (begin < stop) {
      char* newline = static_cast<char*>(std::memchr(begin, '\n', static_cast<std::size_t>(stop - begin)));
      if (newline == nullptr) {
        if (!at_end) break;  // cut: the rest comes with the next read
        newline = stop;      // the last line, without a newline: into the spare byte
      }
      *newline = '\0';
      if (!line(begin, newline, ++number_of_line)) return false;
      begin = newline + 1;
    }
    if (at_end) break;
    kept = begin < stop ? static_cast<std::size_t>(stop - begin) : 0;
    std::memmove(block.data(), begin, kept);
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
