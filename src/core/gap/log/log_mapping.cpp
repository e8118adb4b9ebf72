#include "lane_keeping/gap/log/log_mapping.h"

#include <cmath>
#include <set>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/unique_keys.h"
#include "lane_keeping/config/yaml_position.h"

namespace lane_keeping {
namespace {

const std::vector<std::string>& schemaColumns() {
  static const std::vector<std::string> names{"t",  "x",     "y",          "psi",       "yaw_rate", "v",
                                              "vy", "ay",    "delta",      "delta_rate", "delta_des", "torque"};
  return names;
}

std::string at(const std::string& file, const YAML::Node& node) {
  return yamlPosition(file, node.Mark());
}

[[noreturn]] void fail(const std::string& key, const std::string& location, const std::string& message) {
  throw ConfigError(std::vector<ConfigProblem>{{key, location, message}});
}

double number(const YAML::Node& node, const std::string& key, const std::string& file) {
  double value = 0.0;
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    fail(key, at(file, node), "= '" + YAML::Dump(node) + "' is not a number");
  }
  if (!std::isfinite(value)) fail(key, at(file, node), "= " + YAML::Dump(node) + " must be finite");
  return value;
}

/// A mapping key as a name; a list or mapping as a key ("? [a]: 1") is refused naming file:line.
std::string keyName(const YAML::Node& key, const std::string& where, const std::string& file) {
  if (!key.IsScalar()) fail(where, at(file, key), "a key must be a name, not a list or mapping");
  return key.Scalar();
}

std::string text(const YAML::Node& node, const std::string& key, const std::string& file) {
  if (!node.IsScalar()) fail(key, at(file, node), "must be a column name");
  return node.as<std::string>();
}

}  // namespace

bool isSchemaColumn(const std::string& name) {
  for (const auto& c : schemaColumns()) {
    if (c == name) return true;
  }
  return false;
}

std::string LogMapping::columnFor(const std::string& schema) const {
  if (schema == "t") return time_column;
  const auto it = columns.find(schema);
  return it == columns.end() ? schema : it->second.column;
}

LogMapping logMappingFromYaml(const YAML::Node& section, const std::string& file) {
  LogMapping m;
  m.source = file;
  if (!section.IsMap()) fail("log", at(file, section), "must be a mapping with time: and columns:");
  for (const auto& item : section) {
    const std::string key = keyName(item.first, "log", file);
    if (key != "time" && key != "columns") {
      fail("log." + key, at(file, item.first), "is not a log mapping key (time, columns)");
    }
  }
  if (const YAML::Node time = section["time"]) {
    if (!time.IsMap()) fail("log.time", at(file, time), "must be {column: NAME, unit: s|ms|us|ns}");
    for (const auto& item : time) {
      const std::string key = keyName(item.first, "log.time", file);
      if (key == "column") {
        m.time_column = text(item.second, "log.time.column", file);
      } else if (key == "unit") {
        const std::string unit = text(item.second, "log.time.unit", file);
        if (unit == "s") m.time_scale = 1.0;
        else if (unit == "ms") m.time_scale = 1e-3;
        else if (unit == "us") m.time_scale = 1e-6;
        else if (unit == "ns") m.time_scale = 1e-9;
        else fail("log.time.unit", at(file, item.second), "= " + unit + " is not a time unit (s, ms, us, ns)");
      } else {
        fail("log.time." + key, at(file, item.first), "is not a time mapping key (column, unit)");
      }
    }
  }
  std::set<std::string> used{m.time_column};
  if (const YAML::Node columns = section["columns"]) {
    if (!columns.IsMap()) fail("log.columns", at(file, columns), "must map schema columns to {column: NAME, ...}");
    for (const auto& item : columns) {
      const std::string schema = keyName(item.first, "log.columns", file);
      const std::string key = "log.columns." + schema;
      if (!isSchemaColumn(schema) || schema == "t") {
        fail(key, at(file, item.first),
             "is not a schema column (x, y, psi, yaw_rate, v, vy, ay, delta, delta_rate, delta_des, torque; time goes "
             "under log.time)");
      }
      ColumnMapping c;
      c.location = at(file, item.first);
      if (item.second.IsScalar()) {
        c.column = item.second.as<std::string>();  // short form: delta: steering_angle
      } else if (item.second.IsMap()) {
        for (const auto& field : item.second) {
          const std::string f = keyName(field.first, key, file);
          if (f == "column") c.column = text(field.second, key + ".column", file);
          else if (f == "scale") c.scale = number(field.second, key + ".scale", file);
          else if (f == "offset") c.offset = number(field.second, key + ".offset", file);
          else if (f == "shift") {
            c.shift = number(field.second, key + ".shift", file);
            if (std::fabs(c.shift) > kMaxColumnShift) {
              fail(key + ".shift", at(file, field.second),
                   "= " + YAML::Dump(field.second) + " s: a latency of more than " +
                       std::to_string(static_cast<int>(kMaxColumnShift)) +
                       " s is a clock error, not a sensor's delay (|shift| <= " +
                       std::to_string(static_cast<int>(kMaxColumnShift)) + " s)");
            }
          }
          else if (f == "unscaled") {
            try {
              c.unscaled = field.second.as<bool>();
            } catch (const YAML::Exception&) {
              fail(key + ".unscaled", at(file, field.second), "must be true or false");
            }
          }
          else if (f == "course") {
            if (schema != "psi") fail(key + ".course", at(file, field.first), "applies to psi only (a heading that is the course over ground)");
            try {
              c.course = field.second.as<bool>();
            } catch (const YAML::Exception&) {
              fail(key + ".course", at(file, field.second), "must be true or false");
            }
          }
          else if (f == "speed_of") {
            if (schema != "v") fail(key + ".speed_of", at(file, field.first), "applies to v only (which speed the column holds)");
            const std::string point = field.second.IsScalar() ? field.second.Scalar() : "";
            if (point == "cg") c.speed_of = LoggedSpeed::kCentreOfGravity;
            else if (point == "front_axle") c.speed_of = LoggedSpeed::kFrontAxle;
            else fail(key + ".speed_of", at(file, field.second),
                      "= '" + YAML::Dump(field.second) + "': which speed v holds, cg (the centre of gravity's, the "
                      "default) or front_axle (V of Beregi eq 1, the front axle's speed along its wheel)");
          }
          else if (f == "unit" || f == "note") continue;  // documentation only
          else fail(key + "." + f, at(file, field.first), "is not a column mapping key (column, scale, offset, unscaled, shift, course, speed_of)");
        }
      } else {
        fail(key, at(file, item.second), "must be a column name or {column: NAME, scale: A, offset: B}");
      }
      if (c.column.empty()) fail(key, c.location, "needs column: (the log's column name)");
      if (c.scale == 0.0) fail(key + ".scale", c.location, "= 0: every value would map to the offset");
      if (!used.insert(c.column).second) fail(key, c.location, "column '" + c.column + "' is mapped twice");
      m.columns[schema] = c;
    }
  }
  return m;
}

LogMapping readLogMapping(const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::BadFile&) {
    fail("", file, "cannot read the log mapping file");
  } catch (const YAML::ParserException& e) {
    fail("", file + ":" + std::to_string(e.mark.line + 1), std::string("YAML syntax error: ") + e.msg);
  }
  if (!root.IsMap()) return {};
  checkUniqueKeys(root, file);  // a second `log:` or `columns:` was ignored by a lookup (unique_keys.h)
  if (!root["log"]) return {};
  return logMappingFromYaml(root["log"], file);
}

}  // namespace lane_keeping
