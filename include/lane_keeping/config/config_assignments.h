#pragma once
/// A configuration with "key=value" assignments applied through the configuration's own reader and
/// validate(): the rules a YAML file or `--set` obeys, applied to a configuration already in hand (a
/// runtime change during a run, sim/change_schedule.h). Only the assigned keys are read; validate()
/// then checks the whole result, cross-field rules included.
#include <string>
#include <vector>

#include "lane_keeping/config/sim_config.h"

namespace lane_keeping {

/// `base` with `assignments` ("key=value", value parsed as YAML) applied. Throws ConfigError naming
/// every bad key (unknown, wrong type, out of range, cross-field) with `origin` as its location.
SimConfig withAssignments(const SimConfig& base, const std::vector<std::string>& assignments,
                          const std::string& origin = "--set");

/// The value of `key` in `config` as the configuration prints it ("0.8", "lugre", "[[0, 0], [1, 0]]");
/// throws ConfigError if `key` is not a configuration key.
std::string configValueText(const SimConfig& config, const std::string& key);

}  // namespace lane_keeping
