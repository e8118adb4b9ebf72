#pragma once
/// Parameters of the nodes. The simulation configuration comes from the parameter server in the
/// same schema as the YAML files (the launch file `rosparam load`s config/default.yaml and a scenario
/// into one namespace that every node reads), converted to YAML and passed through the same reader,
/// unknown-key check and validate() as lk_simulate: a bad value fails every node with the same
/// message naming the key. Node options (time mode, timeouts, ...) are private parameters, checked
/// the same way.
#include <string>
#include <vector>

#include <ros/node_handle.h>
#include <xmlrpcpp/XmlRpcValue.h>
#include <yaml-cpp/yaml.h>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/sim_config.h"

namespace lane_keeping {

/// XmlRpc -> YAML: scalars as text (doubles with 17 significant digits, so that they read back
/// bit-identical), arrays as sequences, structs as maps. Throws ConfigError for base64/datetime.
YAML::Node toYaml(const XmlRpc::XmlRpcValue& value, const std::string& key = "");

/// The configuration in the parameter tree `ns` (resolved against nh). Throws ConfigError.
SimConfig loadSimConfigFromParams(const ros::NodeHandle& nh, const std::string& ns);

/// Reads a node's private parameters: absent -> the documented default; present but of the wrong
/// type or out of range -> a problem naming the full key, the value and what is allowed. All
/// problems are reported together by throwIfProblems().
class NodeParamReader {
 public:
  explicit NodeParamReader(const ros::NodeHandle& pnh) : pnh_(pnh) {}

  double number(const std::string& key, double default_value, double min, double max, const std::string& unit);
  bool flag(const std::string& key, bool default_value);
  std::string text(const std::string& key, const std::string& default_value);
  std::string choice(const std::string& key, const std::string& default_value, const std::vector<std::string>& allowed);

  /// Throws ConfigError listing every problem.
  void throwIfProblems() const;
  /// "key: value" lines of everything read, for the startup log.
  const std::string& effective() const { return effective_; }

 private:
  void fail(const std::string& key, const std::string& message);
  void note(const std::string& key, const std::string& value);
  ros::NodeHandle pnh_;
  std::vector<ConfigProblem> problems_;
  std::string effective_;
};

}  // namespace lane_keeping
