#pragma once
/// The ParamVisitor implementations: read from FlatParams, check ranges, print.
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/flat_params.h"
#include "lane_keeping/config/param_visitor.h"

namespace lane_keeping {

/// Reads every visited key that is present in `source` into the struct; records type errors
/// (with file:line) and remembers which keys were used so that unknown keys can be reported.
class FlatParamReader : public ParamVisitor {
 public:
  explicit FlatParamReader(const FlatParams& source) : source_(source) {}

  void number(const std::string& key, double& value, const char* unit, const Range& range, const char* doc) override;
  void optionalNumber(const std::string& key, std::optional<double>& value, const char* unit, const Range& range,
                      const char* doc) override;
  void integer(const std::string& key, int& value, const Range& range, const char* doc) override;
  void flag(const std::string& key, bool& value, const char* doc) override;
  void choice(const std::string& key, std::string& value, const std::vector<std::string>& allowed,
              const char* doc) override;
  void points(const std::string& key, PointList& value, const char* unit, const char* doc) override;

  /// Keys present in the source that no visit asked for (typos), as problems.
  std::vector<ConfigProblem> unknownKeyProblems() const;
  const std::vector<ConfigProblem>& problems() const { return problems_; }
  /// Keys a visit asked for that the source does not hold (they keep their compiled-in defaults),
  /// in visit order; optional numbers (absent = "auto") are not listed.
  const std::vector<std::string>& absentKeys() const { return absent_; }

 private:
  void fail(const std::string& key, const std::string& message);
  const FlatParams& source_;
  std::vector<std::string> absent_;
  std::set<std::string> used_;
  std::vector<ConfigProblem> problems_;
};

/// Checks every number against its Range and every choice against its allowed values.
class RangeChecker : public ParamVisitor {
 public:
  void number(const std::string& key, double& value, const char* unit, const Range& range, const char* doc) override;
  void optionalNumber(const std::string& key, std::optional<double>& value, const char* unit, const Range& range,
                      const char* doc) override;
  void integer(const std::string& key, int& value, const Range& range, const char* doc) override;
  void flag(const std::string&, bool&, const char*) override {}
  void choice(const std::string& key, std::string& value, const std::vector<std::string>& allowed,
              const char* doc) override;
  void points(const std::string& key, PointList& value, const char* unit, const char* doc) override;

  std::vector<ConfigProblem>& problems() { return problems_; }

 private:
  std::vector<ConfigProblem> problems_;
};

/// Prints the parameters as nested YAML ("section:\n  key: value  # [unit] doc"), for logging the
/// effective configuration and for generating config/default.yaml.
class ParamPrinter : public ParamVisitor {
 public:
  explicit ParamPrinter(std::ostream& out, bool with_docs = false) : out_(out), with_docs_(with_docs) {}
  void number(const std::string& key, double& value, const char* unit, const Range& range, const char* doc) override;
  void optionalNumber(const std::string& key, std::optional<double>& value, const char* unit, const Range& range,
                      const char* doc) override;
  void integer(const std::string& key, int& value, const Range& range, const char* doc) override;
  void flag(const std::string& key, bool& value, const char* doc) override;
  void choice(const std::string& key, std::string& value, const std::vector<std::string>& allowed,
              const char* doc) override;
  void points(const std::string& key, PointList& value, const char* unit, const char* doc) override;

 private:
  void line(const std::string& key, const std::string& value, const char* unit, const char* doc);
  std::ostream& out_;
  bool with_docs_;
  std::vector<std::string> open_sections_;
};

/// Collects (key, unit, range, default, doc) rows: config/default.yaml, docs/configuration.md and the ROS
/// parameter adapter use it.
class ParamCatalog : public ParamVisitor {
 public:
  struct Row {
    std::string key, type, unit, range, value, doc;
  };
  void number(const std::string& key, double& value, const char* unit, const Range& range, const char* doc) override;
  void optionalNumber(const std::string& key, std::optional<double>& value, const char* unit, const Range& range,
                      const char* doc) override;
  void integer(const std::string& key, int& value, const Range& range, const char* doc) override;
  void flag(const std::string& key, bool& value, const char* doc) override;
  void choice(const std::string& key, std::string& value, const std::vector<std::string>& allowed,
              const char* doc) override;
  void points(const std::string& key, PointList& value, const char* unit, const char* doc) override;
  const std::vector<Row>& rows() const { return rows_; }

 private:
  std::vector<Row> rows_;
};

/// Shortest round-trip text of a double ("0.0001", "2000000", "1.9019505e-3" style).
std::string formatNumber(double value);

}  // namespace lane_keeping
