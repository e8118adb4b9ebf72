#pragma once
/// The steering replay: the steering degree of freedom (row 3 of Beregi eq 3, the front tire's
/// aligning moment, the steering system) driven by the logged torque, with the logged chassis motion
/// as input, by multiple shooting (replay_shooting.h), against the logged delta.
#include <utility>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/gap/replay/replay_trace.h"

namespace lane_keeping {

/// @param sigma1 the chassis replay's sigma1_estimate (recommended), or nullptr to differentiate positions.
SubsystemReplay replaySteering(const SimConfig& config, const LogSignals& log, const std::vector<TimeSegment>& segments,
                               const ReplayOptions& options = {},
                               const std::vector<std::pair<double, double>>* sigma1 = nullptr);

}  // namespace lane_keeping
