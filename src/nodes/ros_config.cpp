#include "ros_config.h"

#include <cmath>
#include <cstdio>

#include "lane_keeping/config/flat_params.h"
#include "lane_keeping/config/param_readers.h"

namespace lane_keeping {

YAML::Node toYaml(const XmlRpc::XmlRpcValue& value, const std::string& key) {
  XmlRpc::XmlRpcValue& v = const_cast<XmlRpc::XmlRpcValue&>(value);  // XmlRpc's accessors are non-const
  switch (v.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return YAML::Node(static_cast<bool>(v) ? "true" : "false");
    case XmlRpc::XmlRpcValue::TypeInt:
      return YAML::Node(std::to_string(static_cast<int>(v)));
    case XmlRpc::XmlRpcValue::TypeDouble: {
      char buffer[32];
      std::snprintf(buffer, sizeof(buffer), "%.17g", static_cast<double>(v));
      return YAML::Node(std::string(buffer));
    }
    case XmlRpc::XmlRpcValue::TypeString:
      return YAML::Node(static_cast<std::string>(v));
    case XmlRpc::XmlRpcValue::TypeArray: {
      YAML::Node sequence(YAML::NodeType::Sequence);
      for (int i = 0; i < v.size(); ++i) sequence.push_back(toYaml(v[i], key + "[" + std::to_string(i) + "]"));
      return sequence;
    }
    case XmlRpc::XmlRpcValue::TypeStruct: {
      YAML::Node map(YAML::NodeType::Map);
      for (auto it = v.begin(); it != v.end(); ++it) {
        map[it->first] = toYaml(it->second, key.empty() ? it->first : key + "." + it->first);
      }
      return map;
    }
    case XmlRpc::XmlRpcValue::TypeInvalid:
      return YAML::Node(YAML::NodeType::Null);
    default:
      throw ConfigError(std::vector<ConfigProblem>{{key, "", "has an XML-RPC type (base64 or date) that no parameter takes"}});
  }
}

SimConfig loadSimConfigFromParams(const ros::NodeHandle& nh, const std::string& ns) {
  const std::string resolved = nh.resolveName(ns);
  XmlRpc::XmlRpcValue tree;
  if (!nh.getParam(ns, tree)) {
    throw ConfigError("no configuration on the parameter server at " + resolved +
                      " (the launch file loads config/default.yaml and the scenario there with rosparam)");
  }
  if (tree.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
    throw ConfigError(resolved + " must be a parameter tree (vehicle:, tire:, ...), not a single value");
  }
  FlatParams source;
  source.overlayNode(toYaml(tree), "ROS parameters " + resolved);
  // Every node reads the whole tree once at start; a key missing from it would silently take its
  // compiled-in default in this node only, so it is refused, naming the key (issue 16).
  try {
    return simConfigFromFlat(source, MissingKeys::kRefuse);
  } catch (const ConfigError& e) {
    // Problems without a location (a missing key, a cross-field rule) name the tree they concern.
    std::vector<ConfigProblem> problems = e.problems();
    for (ConfigProblem& problem : problems) {
      if (problem.location.empty()) problem.location = "ROS parameters " + resolved;
    }
    throw ConfigError(problems);
  }
}

void NodeParamReader::fail(const std::string& key, const std::string& message) {
  problems_.push_back({pnh_.resolveName(key), "", message});
}

void NodeParamReader::note(const std::string& key, const std::string& value) {
  effective_ += "  " + pnh_.resolveName(key) + ": " + value + "\n";
}

double NodeParamReader::number(const std::string& key, double default_value, double min, double max,
                               const std::string& unit) {
  XmlRpc::XmlRpcValue v;
  double value = default_value;
  if (pnh_.getParam(key, v)) {
    if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) {
      value = static_cast<double>(v);
    } else if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) {
      value = static_cast<int>(v);
    } else {
      fail(key, "= " + v.toXml() + " is not a number (" + unit + ")");
      return default_value;
    }
  }
  if (!std::isfinite(value) || value < min || value > max) {
    fail(key, "= " + formatNumber(value) + " " + unit + ", must be in [" + formatNumber(min) + ", " +
                  formatNumber(max) + "] " + unit);
    return default_value;
  }
  note(key, formatNumber(value) + " " + unit);
  return value;
}

bool NodeParamReader::flag(const std::string& key, bool default_value) {
  XmlRpc::XmlRpcValue v;
  bool value = default_value;
  if (pnh_.getParam(key, v)) {
    if (v.getType() != XmlRpc::XmlRpcValue::TypeBoolean) {
      fail(key, "= " + v.toXml() + " is not a boolean (true or false)");
      return default_value;
    }
    value = static_cast<bool>(v);
  }
  note(key, value ? "true" : "false");
  return value;
}

std::string NodeParamReader::text(const std::string& key, const std::string& default_value) {
  XmlRpc::XmlRpcValue v;
  std::string value = default_value;
  if (pnh_.getParam(key, v)) {
    if (v.getType() != XmlRpc::XmlRpcValue::TypeString) {
      fail(key, "= " + v.toXml() + " is not a string");
      return default_value;
    }
    value = static_cast<std::string>(v);
  }
  note(key, "'" + value + "'");
  return value;
}

std::string NodeParamReader::choice(const std::string& key, const std::string& default_value,
                                    const std::vector<std::string>& allowed) {
  const std::size_t problems_before = problems_.size();
  const std::string value = text(key, default_value);
  if (problems_.size() != problems_before) return default_value;
  for (const auto& a : allowed) {
    if (a == value) return value;
  }
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
  fail(key, "= '" + value + "' is not one of: " + list);
  return default_value;
}

void NodeParamReader::throwIfProblems() const {
  if (!problems_.empty()) throw ConfigError(problems_);
}

}  // namespace lane_keeping
