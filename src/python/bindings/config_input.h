#pragma once
// Configurations handed over by Python, as the core's FlatParams: the Python package (lane_keeping/
// _config.py) turns whatever the user gave (a path, YAML text, a nested dict, a list of them) into a
// list of layers, each overlaid in order on the paper's defaults exactly as lk_simulate overlays
// --config files and --set assignments:
//   ("file", path)               FlatParams::overlayFile
//   ("text", yaml, origin)       FlatParams::overlayText (errors name origin:line)
//   ("dict", mapping, origin)    a YAML node built from the dict, FlatParams::overlayNode
//   ("set", "key=value", origin) FlatParams::overlayAssignment
#include <string>
#include <vector>

#include <pybind11/pybind11.h>
#include <yaml-cpp/yaml.h>

#include "lane_keeping/config/flat_params.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/config/timed_change.h"
#include "lane_keeping/gap/log/log_mapping.h"

namespace lane_keeping {
namespace python {

/// A YAML node of a plain Python value (dict, list or tuple, str, bool, int, float, None). Floats keep
/// every bit (Python's repr reads back to the same double). `key` names the value in errors.
YAML::Node yamlOf(pybind11::handle value, const std::string& key);
/// The layers overlaid in order.
FlatParams flatParamsOf(pybind11::handle layers);
/// The configuration of the layers: loadSimConfig(FlatParams) (a `log:` section is ignored).
SimConfig simConfigOf(pybind11::handle layers);
/// The `log:` mapping of the layers (the last layer that has one), as lk_gap reads it from --config files.
LogMapping logMappingOf(pybind11::handle layers);
/// "T:key=value" texts, parsed by the core (parseTimedChange).
std::vector<TimedChange> timedChangesOf(pybind11::handle texts);

}  // namespace python
}  // namespace lane_keeping
