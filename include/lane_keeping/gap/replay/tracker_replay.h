#pragma once
/// The tracker's replay: Beregi eq 11 on the logged pose delayed by tau1 (algebraic), against the
/// logged delta_des.
#include <utility>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/gap/replay/replay_trace.h"

namespace lane_keeping {

SubsystemReplay replayTracker(const SimConfig& config, const LogSignals& log, const std::vector<TimeSegment>& segments);

}  // namespace lane_keeping
