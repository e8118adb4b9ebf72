#include "lane_keeping/config/param_readers.h"
#include "lane_keeping/config/points_file.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace lane_keeping {

// ----------------------------------------------------------------------------------------------
// Range
// ----------------------------------------------------------------------------------------------
bool Range::contains(double value) const {
  if (!std::isfinite(value)) return false;
  if (min_inclusive ? value < min : value <= min) return false;
  if (max_inclusive ? value > max : value >= max) return false;
  return true;
}

std::string Range::describe() const {
  const bool has_min = std::isfinite(min);
  const bool has_max = std::isfinite(max);
  if (!has_min && !has_max) return "any finite number";
  if (has_min && !has_max) return std::string(min_inclusive ? ">= " : "> ") + formatNumber(min);
  if (!has_min && has_max) return std::string(max_inclusive ? "<= " : "< ") + formatNumber(max);
  return std::string("in ") + (min_inclusive ? "[" : "(") + formatNumber(min) + ", " + formatNumber(max) +
         (max_inclusive ? "]" : ")");
}

std::string formatNumber(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof(buffer), "%.*g", precision, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

namespace {

std::string withUnit(const std::string& text, const char* unit) {
  if (unit == nullptr || unit[0] == '\0') return text;
  return text + " " + unit;
}

std::string scalarText(const YAML::Node& node) {
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a mapping";
  return "null";
}

/// Parses a YAML scalar as a double, accepting .nan/.inf so that they can be rejected by name.
bool parseDouble(const YAML::Node& node, double* out) {
  if (!node.IsScalar()) return false;
  try {
    *out = node.as<double>();
    return true;
  } catch (const YAML::BadConversion&) {
    return false;
  }
}

}  // namespace

// ----------------------------------------------------------------------------------------------
// FlatParamReader
// ----------------------------------------------------------------------------------------------
void FlatParamReader::fail(const std::string& key, const std::string& message) {
  problems_.push_back(ConfigProblem{key, source_.locationOf(key), message});
}

void FlatParamReader::number(const std::string& key, double& value, const char* unit, const Range&,
                             const char*) {
  const FlatParams::Entry* entry = source_.find(key);
  if (entry == nullptr) {
    absent_.push_back(key);
    return;
  }
  used_.insert(key);
  double parsed = 0.0;
  if (!parseDouble(entry->value, &parsed)) {
    fail(key, "= " + scalarText(entry->value) + ": expected a number" + (unit && unit[0] ? std::string(" in ") + unit : ""));
    return;
  }
  value = parsed;  // range (and NaN/Inf) checked by validate() through RangeChecker
}

void FlatParamReader::optionalNumber(const std::string& key, std::optional<double>& value, const char* unit,
                                     const Range& range, const char* doc) {
  const FlatParams::Entry* entry = source_.find(key);
  if (entry == nullptr) return;
  used_.insert(key);
  if (entry->value.IsNull() || (entry->value.IsScalar() && entry->value.Scalar() == "auto")) {
    value.reset();
    return;
  }
  double parsed = 0.0;
  number(key, parsed, unit, range, doc);
  if (parseDouble(entry->value, &parsed)) value = parsed;
}

void FlatParamReader::integer(const std::string& key, int& value, const Range&, const char*) {
  const FlatParams::Entry* entry = source_.find(key);
  if (entry == nullptr) {
    absent_.push_back(key);
    return;
  }
  used_.insert(key);
  double parsed = 0.0;
  if (!parseDouble(entry->value, &parsed) || !std::isfinite(parsed) || parsed != std::floor(parsed) ||
      std::fabs(parsed) > 2e9) {
    fail(key, "= " + scalarText(entry->value) + ": expected an integer");
    return;
  }
  value = static_cast<int>(parsed);
}

void FlatParamReader::flag(const std::string& key, bool& value, const char*) {
  const FlatParams::Entry* entry = source_.find(key);
  if (entry == nullptr) {
    absent_.push_back(key);
    return;
  }
  used_.insert(key);
  try {
    value = entry->value.as<bool>();
  } catch (const YAML::BadConversion&) {
    fail(key, "= " + scalarText(entry->value) + ": expected true or false");
  }
}

void FlatParamReader::choice(const std::string& key, std::string& value, const std::vector<std::string>& allowed,
                             const char*) {
  const FlatParams::Entry* entry = source_.find(key);
  if (entry == nullptr) {
    absent_.push_back(key);
    return;
  }
  used_.insert(key);
  if (!entry->value.IsScalar()) {
    fail(key, "= " + scalarText(entry->value) + ": expected one of the names listed in docs/configuration.md");
    return;
  }
  value = entry->value.Scalar();  // membership checked by RangeChecker (names the allowed values)
  (void)allowed;
}

void FlatParamReader::points(const std::string& key, PointList& value, const char*, const char*) {
  const FlatParams::Entry* entry = source_.find(key);
  if (entry == nullptr) {
    absent_.push_back(key);
    return;
  }
  used_.insert(key);
  if (entry->value.IsScalar()) {
    // A file of points (points_file.h), beside the configuration file that names it.
    std::vector<Point2> parsed;
    std::string error;
    if (!readPointsCsv(resolveBeside(entry->value.Scalar(), entry->location), &parsed, &error)) {
      fail(key, "= " + entry->value.Scalar() + ": " + error);
      return;
    }
    value = PointList(std::move(parsed));
    return;
  }
  if (!entry->value.IsSequence()) {
    fail(key, "= " + scalarText(entry->value) + ": expected a list of [x, y] pairs, or the name of a CSV file of them");
    return;
  }
  std::vector<Point2> parsed;
  for (std::size_t i = 0; i < entry->value.size(); ++i) {
    const YAML::Node& item = entry->value[i];
    Point2 point{0.0, 0.0};
    if (!item.IsSequence() || item.size() != 2 || !parseDouble(item[0], &point[0]) ||
        !parseDouble(item[1], &point[1])) {
      fail(key, "[" + std::to_string(i) + "]: expected a pair [x, y] of numbers");
      return;
    }
    parsed.push_back(point);
  }
  value = PointList(std::move(parsed));
}

std::vector<ConfigProblem> FlatParamReader::unknownKeyProblems() const {
  std::vector<ConfigProblem> problems;
  for (const auto& [key, entry] : source_.entries()) {
    if (used_.count(key) == 0) {
      problems.push_back(ConfigProblem{key, entry.location, "is not a known parameter (typo?)"});
    }
  }
  return problems;
}

// ----------------------------------------------------------------------------------------------
// RangeChecker
// ----------------------------------------------------------------------------------------------
void RangeChecker::number(const std::string& key, double& value, const char* unit, const Range& range,
                          const char*) {
  if (!range.contains(value)) {
    problems_.push_back(ConfigProblem{key, "", "= " + withUnit(formatNumber(value), unit) + ", must be " +
                                                   withUnit(range.describe(), unit)});
  }
}

void RangeChecker::optionalNumber(const std::string& key, std::optional<double>& value, const char* unit,
                                  const Range& range, const char* doc) {
  if (value) number(key, *value, unit, range, doc);
}

void RangeChecker::integer(const std::string& key, int& value, const Range& range, const char*) {
  if (!range.contains(static_cast<double>(value))) {
    problems_.push_back(ConfigProblem{key, "", "= " + std::to_string(value) + ", must be " + range.describe()});
  }
}

void RangeChecker::choice(const std::string& key, std::string& value, const std::vector<std::string>& allowed,
                          const char*) {
  if (allowed.empty()) return;  // free text (names, descriptions)
  for (const auto& name : allowed) {
    if (name == value) return;
  }
  std::string list;
  for (const auto& name : allowed) list += (list.empty() ? "" : ", ") + name;
  problems_.push_back(ConfigProblem{key, "", "= '" + value + "' is unknown; allowed: " + list});
}

void RangeChecker::points(const std::string& key, PointList& value, const char*, const char*) {
  for (std::size_t i = 0; i < value.size(); ++i) {
    if (!std::isfinite(value[i][0]) || !std::isfinite(value[i][1])) {
      problems_.push_back(ConfigProblem{key, "", "[" + std::to_string(i) + "] is not finite"});
    }
  }
}

// ----------------------------------------------------------------------------------------------
// ParamPrinter
// ----------------------------------------------------------------------------------------------
void ParamPrinter::line(const std::string& key, const std::string& value, const char* unit, const char* doc) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t dot = key.find('.'); dot != std::string::npos; dot = key.find('.', start)) {
    parts.push_back(key.substr(start, dot - start));
    start = dot + 1;
  }
  const std::string leaf = key.substr(start);
  std::size_t common = 0;
  while (common < parts.size() && common < open_sections_.size() && parts[common] == open_sections_[common]) ++common;
  for (std::size_t i = common; i < parts.size(); ++i) {
    out_ << std::string(2 * i, ' ') << parts[i] << ":\n";
  }
  open_sections_ = parts;
  out_ << std::string(2 * parts.size(), ' ') << leaf << ": " << value;
  if ((unit && unit[0]) || (with_docs_ && doc && doc[0])) {
    out_ << "  #";
    if (unit && unit[0]) out_ << " [" << unit << "]";
    if (with_docs_ && doc && doc[0]) out_ << " " << doc;
  }
  out_ << "\n";
}

void ParamPrinter::number(const std::string& key, double& value, const char* unit, const Range&, const char* doc) {
  line(key, formatNumber(value), unit, doc);
}
void ParamPrinter::optionalNumber(const std::string& key, std::optional<double>& value, const char* unit,
                                  const Range&, const char* doc) {
  line(key, value ? formatNumber(*value) : "auto", unit, doc);
}
void ParamPrinter::integer(const std::string& key, int& value, const Range&, const char* doc) {
  line(key, std::to_string(value), nullptr, doc);
}
void ParamPrinter::flag(const std::string& key, bool& value, const char* doc) {
  line(key, value ? "true" : "false", nullptr, doc);
}
void ParamPrinter::choice(const std::string& key, std::string& value, const std::vector<std::string>& allowed,
                          const char* doc) {
  if (!allowed.empty()) {
    line(key, value, nullptr, doc);
    return;
  }
  std::string quoted = "\"";
  for (char c : value) quoted += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  line(key, quoted + "\"", nullptr, doc);
}
void ParamPrinter::points(const std::string& key, PointList& value, const char* unit, const char* doc) {
  std::ostringstream text;
  text << "[";
  for (std::size_t i = 0; i < value.size(); ++i) {
    text << (i ? ", " : "") << "[" << formatNumber(value[i][0]) << ", " << formatNumber(value[i][1]) << "]";
  }
  text << "]";
  line(key, text.str(), unit, doc);
}

// ----------------------------------------------------------------------------------------------
// ParamCatalog
// ----------------------------------------------------------------------------------------------
void ParamCatalog::number(const std::string& key, double& value, const char* unit, const Range& range,
                          const char* doc) {
  rows_.push_back(Row{key, "double", unit ? unit : "", range.describe(), formatNumber(value), doc ? doc : ""});
}
void ParamCatalog::optionalNumber(const std::string& key, std::optional<double>& value, const char* unit,
                                  const Range& range, const char* doc) {
  rows_.push_back(Row{key, "double or auto", unit ? unit : "", range.describe(),
                      value ? formatNumber(*value) : "auto", doc ? doc : ""});
}
void ParamCatalog::integer(const std::string& key, int& value, const Range& range, const char* doc) {
  rows_.push_back(Row{key, "int", "", range.describe(), std::to_string(value), doc ? doc : ""});
}
void ParamCatalog::flag(const std::string& key, bool& value, const char* doc) {
  rows_.push_back(Row{key, "bool", "", "true/false", value ? "true" : "false", doc ? doc : ""});
}
void ParamCatalog::choice(const std::string& key, std::string& value, const std::vector<std::string>& allowed,
                          const char* doc) {
  std::string list;
  for (const auto& name : allowed) list += (list.empty() ? "" : " | ") + name;
  rows_.push_back(Row{key, "string", "", list, value, doc ? doc : ""});
}
void ParamCatalog::points(const std::string& key, PointList& value, const char* unit, const char* doc) {
  rows_.push_back(Row{key, "[[x, y], ...]", unit ? unit : "", "finite", std::to_string(value.size()) + " points",
                      doc ? doc : ""});
}

}  // namespace lane_keeping
