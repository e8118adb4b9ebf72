#include "lane_keeping/common/command_line.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {
namespace {

std::string shortest(double value) {
  char buffer[32];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof(buffer), "%.*g", precision, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

/// The whole of `text` as a double (from_chars: no locale, no leading blanks, no trailing characters).
bool parseWhole(const std::string& text, double* value) {
  const char* first = text.data();
  const char* last = first + text.size();
  if (first != last && *first == '+') {  // "+5" reads as 5, as strtod would ("+-5" does not)
    ++first;
    if (first != last && *first == '-') return false;
  }
  if (first == last) return false;
  const auto [end, error] = std::from_chars(first, last, *value);
  return error == std::errc() && end == last;
}

std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof(hex), "\\x%02x", u);
      out += hex;
    } else {
      out += c;
    }
  }
  return out + "'";
}

}  // namespace

double numberOption(const std::string& option, const std::string& text, double min, double max,
                    const std::string& unit) {
  double value = 0.0;
  const std::string u = unit.empty() ? "" : " " + unit;
  if (!parseWhole(text, &value) || !std::isfinite(value)) {
    throw UsageError(option + ": " + quoted(text) + " is not a number (expected one in [" + shortest(min) + ", " +
                     shortest(max) + "]" + u + ")");
  }
  if (value < min || value > max) {
    throw UsageError(option + ": " + text + u + " is out of range: must be in [" + shortest(min) + ", " +
                     shortest(max) + "]" + u);
  }
  return value;
}

long long wholeNumberOption(const std::string& option, const std::string& text, long long min, long long max) {
  double value = 0.0;
  const std::string range = "[" + std::to_string(min) + ", " + std::to_string(max) + "]";
  if (!parseWhole(text, &value) || !std::isfinite(value) || value != std::floor(value)) {
    throw UsageError(option + ": " + quoted(text) + " is not a whole number (expected one in " + range + ")");
  }
  if (value < static_cast<double>(min) || value > static_cast<double>(max)) {
    throw UsageError(option + ": " + text + " is out of range: must be in " + range);
  }
  return static_cast<long long>(value);
}

}  // namespace lane_keeping
