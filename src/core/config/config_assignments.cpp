#include "lane_keeping/config/config_assignments.h"

#include <sstream>

#include "lane_keeping/config/param_readers.h"

namespace lane_keeping {

SimConfig withAssignments(const SimConfig& base, const std::vector<std::string>& assignments,
                          const std::string& origin) {
  FlatParams source;
  for (const auto& assignment : assignments) source.overlayAssignment(assignment, origin);
  // The same steps as simConfigFromFlat(), on a copy of `base` instead of the defaults: keys absent
  // from `source` keep their values.
  SimConfig out = base;
  FlatParamReader reader(source);
  out.visit(reader);
  std::vector<ConfigProblem> problems = reader.problems();
  const auto unknown = reader.unknownKeyProblems();
  problems.insert(problems.end(), unknown.begin(), unknown.end());
  if (!problems.empty()) throw ConfigError(problems);
  out.validate(&source);
  return out;
}

namespace {

/// Finds one key's value text through the printer's own formatting (the visitor sees every field).
class ValueFinder : public ParamVisitor {
 public:
  explicit ValueFinder(std::string key) : key_(std::move(key)) {}
  void number(const std::string& key, double& value, const char*, const Range&, const char*) override {
    if (key == key_) found(formatNumber(value));
  }
  void optionalNumber(const std::string& key, std::optional<double>& value, const char*, const Range&,
                      const char*) override {
    if (key == key_) found(value ? formatNumber(*value) : std::string("auto"));
  }
  void integer(const std::string& key, int& value, const Range&, const char*) override {
    if (key == key_) found(std::to_string(value));
  }
  void flag(const std::string& key, bool& value, const char*) override {
    if (key == key_) found(value ? "true" : "false");
  }
  void choice(const std::string& key, std::string& value, const std::vector<std::string>&, const char*) override {
    if (key == key_) found(value);
  }
  void points(const std::string& key, PointList& value, const char*, const char*) override {
    if (key != key_) return;
    std::ostringstream out;
    out << "[";
    for (std::size_t i = 0; i < value.size(); ++i) {
      out << (i ? ", " : "") << "[" << formatNumber(value[i][0]) << ", " << formatNumber(value[i][1]) << "]";
    }
    out << "]";
    found(out.str());
  }
  bool has_value = false;
  std::string value;

 private:
  void found(std::string text) {
    has_value = true;
    value = std::move(text);
  }
  std::string key_;
};

}  // namespace

std::string configValueText(const SimConfig& config, const std::string& key) {
  SimConfig copy = config;  // visit() takes non-const references
  ValueFinder finder(key);
  copy.visit(finder);
  if (!finder.has_value) throw ConfigError(std::vector<ConfigProblem>{{key, "", "is not a known parameter (typo?)"}});
  return finder.value;
}

}  // namespace lane_keeping
