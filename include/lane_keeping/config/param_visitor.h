#pragma once
/// Self-documenting parameters (the Drake `named_vector` idea): every parameter struct has one
/// `visit(ParamVisitor&, prefix)` that names each field with its full dotted key, unit, allowed
/// range and meaning. Reading YAML, reading ROS parameters, range validation, printing the
/// effective configuration and config/default.yaml all walk the same list, so they cannot drift.
#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "lane_keeping/config/point_list.h"

namespace lane_keeping {

/// Allowed interval of a number; NaN and infinities are never allowed.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_inclusive = true;
  bool max_inclusive = true;

  static Range any() { return Range{}; }
  static Range positive() { return Range{0.0, std::numeric_limits<double>::infinity(), false, true}; }
  static Range nonNegative() { return Range{0.0, std::numeric_limits<double>::infinity(), true, true}; }
  static Range closed(double lo, double hi) { return Range{lo, hi, true, true}; }
  static Range open(double lo, double hi) { return Range{lo, hi, false, false}; }
  static Range atLeast(double lo) { return Range{lo, std::numeric_limits<double>::infinity(), true, true}; }

  bool contains(double value) const;
  /// "> 0", ">= 0", "in [0, 1]", "in (0, 1.5708)", "any finite number".
  std::string describe() const;
};


/// Visitor over parameter fields. `key` is always the full dotted key ("tire.front.mu").
class ParamVisitor {
 public:
  virtual ~ParamVisitor() = default;
  virtual void number(const std::string& key, double& value, const char* unit, const Range& range,
                      const char* doc) = 0;
  /// A number that may be left unset (null/absent) to take a derived default that `doc` explains.
  virtual void optionalNumber(const std::string& key, std::optional<double>& value, const char* unit,
                              const Range& range, const char* doc) = 0;
  virtual void integer(const std::string& key, int& value, const Range& range, const char* doc) = 0;
  virtual void flag(const std::string& key, bool& value, const char* doc) = 0;
  virtual void choice(const std::string& key, std::string& value, const std::vector<std::string>& allowed,
                      const char* doc) = 0;
  virtual void points(const std::string& key, PointList& value, const char* unit, const char* doc) = 0;
};

}  // namespace lane_keeping
