#pragma once
/// The chassis replay: rows 1-2 of Beregi eq 3 and eq 2 driven by the logged steering motion, by
/// multiple shooting (replay_shooting.h), against the logged yaw rate, psi, y and a_y. A log without a
/// pose (what a vehicle bus gives: speed, steering angle, yaw rate, perhaps a_y) is replayed on the
/// lateral dynamics alone: yaw rate and a_y compared, the lateral velocity estimated per interval.
#include <utility>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/gap/replay/replay_trace.h"

namespace lane_keeping {

SubsystemReplay replayChassis(const SimConfig& config, const LogSignals& log, const std::vector<TimeSegment>& segments,
                              const ReplayOptions& options = {});

}  // namespace lane_keeping
