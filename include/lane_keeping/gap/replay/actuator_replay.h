#pragma once
/// The actuator's replay: eqs 12-13 on the logged delta_des and delta delayed by tau2, against the
/// logged torque command (the unknown initial integral is a constant offset, removed by least squares).
#include <utility>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/gap/replay/replay_trace.h"

namespace lane_keeping {

SubsystemReplay replayActuator(const SimConfig& config, const LogSignals& log, const std::vector<TimeSegment>& segments);

}  // namespace lane_keeping
