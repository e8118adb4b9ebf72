#pragma once
/// A change of configuration tested against logged runs: a candidate effect with its parameters, or a
/// benchmark's truth overlay. Each run has its own configuration (gap_run.h); a change is applied to
/// each of them, so that one effect is tested on runs of different roads and initial states.
#include <functional>
#include <string>
#include <vector>

#include "lane_keeping/config/sim_config.h"

namespace lane_keeping {

using ConfigChange = std::function<void(SimConfig&)>;

/// The change that sets `assignments` ("key=value", as --set takes them) through the configuration
/// reader; applying it throws ConfigError naming the key if a value is invalid.
ConfigChange assignmentsChange(std::vector<std::string> assignments);

/// `base` with `change` applied (`change` may be empty: no change).
SimConfig changed(const SimConfig& base, const ConfigChange& change);

}  // namespace lane_keeping
