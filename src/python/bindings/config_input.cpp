#include "config_input.h"

#include <cmath>

#include "lane_keeping/common/errors.h"

namespace py = pybind11;

namespace lane_keeping {
namespace python {
namespace {

std::string textOf(py::handle value) { return py::str(value).cast<std::string>(); }

ConfigError badValue(const std::string& key, const std::string& why) {
  return ConfigError(std::vector<ConfigProblem>{{key, "<dict>", why}});
}

}  // namespace

YAML::Node yamlOf(py::handle value, const std::string& key) {
  if (value.is_none()) return YAML::Node(YAML::NodeType::Null);
  if (py::isinstance<py::bool_>(value)) return YAML::Node(value.cast<bool>() ? "true" : "false");
  if (py::isinstance<py::int_>(value)) return YAML::Node(textOf(value));
  if (py::isinstance<py::float_>(value)) {
    const double v = value.cast<double>();
    // YAML's spelling of the non-finite values (the reader then refuses them naming the key).
    if (std::isnan(v)) return YAML::Node(".nan");
    if (std::isinf(v)) return YAML::Node(v > 0 ? ".inf" : "-.inf");
    return YAML::Node(py::repr(value).cast<std::string>());
  }
  if (py::isinstance<py::str>(value)) return YAML::Node(value.cast<std::string>());
  if (py::isinstance<py::dict>(value)) {
    YAML::Node map(YAML::NodeType::Map);
    for (const auto& item : value.cast<py::dict>()) {
      if (!py::isinstance<py::str>(item.first)) {
        throw badValue(key, "a key must be a name (a str), found " + py::repr(item.first).cast<std::string>());
      }
      const std::string name = item.first.cast<std::string>();
      map[name] = yamlOf(item.second, key.empty() ? name : key + "." + name);
    }
    return map;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    YAML::Node sequence(YAML::NodeType::Sequence);
    for (const auto& item : value) sequence.push_back(yamlOf(item, key));
    return sequence;
  }
  throw badValue(key, "= " + py::repr(value).cast<std::string>() + " (" +
                          py::str(py::type::of(value).attr("__name__")).cast<std::string>() +
                          ") is not a number, string, bool, list or mapping");
}

FlatParams flatParamsOf(py::handle layers) {
  FlatParams params;
  for (const auto& item : layers) {
    const py::tuple layer = item.cast<py::tuple>();
    const std::string kind = layer[0].cast<std::string>();
    if (kind == "file") {
      params.overlayFile(layer[1].cast<std::string>());
    } else if (kind == "text") {
      params.overlayText(layer[1].cast<std::string>(), layer[2].cast<std::string>());
    } else if (kind == "dict") {
      params.overlayNode(yamlOf(layer[1], ""), layer[2].cast<std::string>());
    } else if (kind == "set") {
      params.overlayAssignment(layer[1].cast<std::string>(), layer[2].cast<std::string>());
    } else {
      throw std::invalid_argument("configuration layer of unknown kind '" + kind + "'");
    }
  }
  return params;
}

SimConfig simConfigOf(py::handle layers) { return loadSimConfig(flatParamsOf(layers)); }

LogMapping logMappingOf(py::handle layers) {
  LogMapping mapping;
  for (const auto& item : layers) {
    const py::tuple layer = item.cast<py::tuple>();
    const std::string kind = layer[0].cast<std::string>();
    LogMapping m;
    if (kind == "file") {
      m = readLogMapping(layer[1].cast<std::string>());
    } else if (kind == "text" || kind == "dict") {
      const std::string origin = layer[2].cast<std::string>();
      YAML::Node root;
      if (kind == "dict") {
        root = yamlOf(layer[1], "");
      } else {
        try {
          root = YAML::Load(layer[1].cast<std::string>());
        } catch (const YAML::Exception&) {
          continue;  // flatParamsOf reports malformed YAML with its line
        }
      }
      const YAML::Node& document = root;  // const: operator[] would add the key
      if (document.IsMap() && document["log"]) m = logMappingFromYaml(document["log"], origin);
    }
    if (!m.source.empty()) mapping = m;
  }
  return mapping;
}

std::vector<TimedChange> timedChangesOf(py::handle texts) {
  std::vector<TimedChange> changes;
  if (texts.is_none()) return changes;
  for (const auto& text : texts) changes.push_back(parseTimedChange(text.cast<std::string>()));
  return changes;
}

}  // namespace python
}  // namespace lane_keeping
